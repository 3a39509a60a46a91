#include "haptics/device_config.h"

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine {

SeatConfig ParseSeatConfig(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(source, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("devices") || !j["devices"].is_array())
    throw Error(source, "expected an object with a \"devices\" array");
  SeatConfig config;
  int index = 0;
  for (const auto& d : j["devices"]) {
    const std::string where = "devices[" + std::to_string(index++) + "]";
    if (!d.is_object()) throw Error(source, where + " is not an object");
    if (!d.contains("role") || !d["role"].is_string())
      throw Error(source, where + ": missing \"role\"");
    if (!d.contains("serial") || !d["serial"].is_string() || d["serial"].get<std::string>().empty())
      throw Error(source, where +
                              ": missing \"serial\" (the FTDI serial number; `hapcine play "
                              "--device falcon` lists them)");
    const std::string role = d["role"];
    int a = -1;
    if (role == "head") a = 0;
    if (role == "left") a = 1;
    if (role == "right") a = 2;
    if (a < 0) throw Error(source, where + ": role '" + role + "' is not head, left or right");
    if (config.roles[a]) throw Error(source, where + ": role '" + role + "' given twice");
    SeatDeviceConfig c;
    c.serial = d["serial"];
    if (d.contains("seat_from_falcon")) {
      const auto& m = d["seat_from_falcon"];
      if (!m.is_array() || m.size() != 3)
        throw Error(source, where + ": seat_from_falcon must be 3 rows");
      for (int r = 0; r < 3; ++r) {
        if (!m[r].is_array() || m[r].size() != 3)
          throw Error(source, where + ": seat_from_falcon must be 3x3");
        for (int k = 0; k < 3; ++k) {
          if (!m[r][k].is_number())
            throw Error(source, where + ": seat_from_falcon has a non-number");
          c.seat_from_falcon(r, k) = m[r][k].get<double>();
        }
      }
      const double ortho =
          (c.seat_from_falcon * c.seat_from_falcon.transpose() - Eigen::Matrix3d::Identity())
              .norm();
      if (!(ortho < 1e-6) || !(std::abs(c.seat_from_falcon.determinant() - 1) < 1e-6))
        throw Error(source, where + ": seat_from_falcon is not a rotation");
    } else if (d.contains("mount")) {
      if (!d["mount"].is_string())
        throw Error(source, where + ": mount must be \"front\" or \"behind\"");
      const std::string mount = d["mount"];
      if (mount == "behind") {
        c.seat_from_falcon = Eigen::Vector3d(-1, 1, -1).asDiagonal();
      } else if (mount != "front") {
        throw Error(source, where + ": mount '" + mount + "' is not \"front\" or \"behind\"");
      }
    }
    if (d.contains("max_force_n")) {
      if (!d["max_force_n"].is_number())
        throw Error(source, where + ": max_force_n must be a number");
      const double f = d["max_force_n"];
      if (!(f > 0 && f <= 9)) throw Error(source, where + ": max_force_n must be in (0, 9] N");
      c.max_force_n = f;
    }
    for (int other = 0; other < kNumActuators; ++other)
      if (config.roles[other] && config.roles[other]->serial == c.serial)
        throw Error(source, where + ": serial '" + c.serial + "' mapped to two roles");
    config.roles[a] = c;
  }
  return config;
}

SeatConfig ReadSeatConfigFile(const std::string& path) {
  InputFile in(path);
  std::stringstream s;
  s << in.stream().rdbuf();
  return ParseSeatConfig(s.str(), path);
}

}  // namespace hapcine
