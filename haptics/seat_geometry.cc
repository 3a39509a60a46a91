#include "haptics/seat_geometry.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine {
namespace {

using nlohmann::json;

Eigen::Vector3d ReadVec(const json& j, const std::string& key, const std::string& src) {
  if (!j.is_array() || j.size() != 3)
    throw Error(src, "'" + key + "' must be an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw Error(src, "'" + key + "' must be an array of 3 numbers");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) throw Error(src, "'" + key + "' is not finite");
  }
  return v;
}

double ReadNum(const json& j, const std::string& key, const std::string& src) {
  if (!j.is_number()) throw Error(src, "'" + key + "' must be a number");
  return j.get<double>();
}

json VecJson(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

void SeatGeometry::Check() const {
  auto finite = [](const Eigen::Vector3d& v) { return v.allFinite(); };
  if (!finite(center_m)) throw UsageError("seat: centre is not finite");
  for (int a = 0; a < kNumActuators; ++a) {
    if (!finite(rest_m[a])) throw UsageError("seat: actuator position is not finite");
    if (FromCenter(a).norm() < 1e-3) {
      throw UsageError(std::string("seat: actuator '") + ActuatorName(static_cast<Actuator>(a)) +
                       "' sits at the centre G (rotations would not move it)");
    }
    if (FromCenter(a).norm() > 5.0) throw UsageError("seat: actuator more than 5 m from G");
  }
  if (!(usable_half_m > 0 && usable_half_m <= clamp_half_m && clamp_half_m <= workspace_half_m &&
        workspace_half_m <= 1.0)) {
    throw UsageError("seat: need 0 < usable_half_m <= clamp_half_m <= workspace_half_m <= 1");
  }
  if (!(rate_hz >= 10 && rate_hz <= 10000))
    throw UsageError("seat: rate_hz must be in [10, 10000]");
}

SeatGeometry ParseSeatGeometryJson(const std::string& text, const std::string& src) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // also out_of_range: a number beyond double's range
    throw Error(src, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw Error(src, "seat geometry must be a JSON object");
  SeatGeometry seat;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    if (k == "center_m")
      seat.center_m = ReadVec(*it, k, src);
    else if (k == "head_m")
      seat.rest_m[0] = ReadVec(*it, k, src);
    else if (k == "left_hand_m")
      seat.rest_m[1] = ReadVec(*it, k, src);
    else if (k == "right_hand_m")
      seat.rest_m[2] = ReadVec(*it, k, src);
    else if (k == "workspace_half_m")
      seat.workspace_half_m = ReadNum(*it, k, src);
    else if (k == "usable_half_m")
      seat.usable_half_m = ReadNum(*it, k, src);
    else if (k == "clamp_half_m")
      seat.clamp_half_m = ReadNum(*it, k, src);
    else if (k == "rate_hz")
      seat.rate_hz = ReadNum(*it, k, src);
    else if (k == "comment" || k == "_comment")
      continue;
    else
      throw Error(src, "unknown key '" + k + "'");
  }
  try {
    seat.Check();
  } catch (const UsageError& e) {
    throw Error(src, e.what());
  }
  return seat;
}

SeatGeometry LoadSeatGeometryFile(const std::string& path) {
  InputFile in(path);
  std::stringstream ss;
  ss << in.stream().rdbuf();
  return ParseSeatGeometryJson(ss.str(), path);
}

std::string SeatGeometryToJson(const SeatGeometry& s) {
  json j;
  j["center_m"] = VecJson(s.center_m);
  j["head_m"] = VecJson(s.rest_m[0]);
  j["left_hand_m"] = VecJson(s.rest_m[1]);
  j["right_hand_m"] = VecJson(s.rest_m[2]);
  j["workspace_half_m"] = s.workspace_half_m;
  j["usable_half_m"] = s.usable_half_m;
  j["clamp_half_m"] = s.clamp_half_m;
  j["rate_hz"] = s.rate_hz;
  return j.dump(2) + "\n";
}

}  // namespace hapcine
