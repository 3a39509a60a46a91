#include "datasets/tum_format.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/rotation.h"

namespace hapcine {

std::vector<double> ParseNumberFields(const std::string& line, const std::string& where) {
  std::istringstream fields(line);
  std::vector<double> v;
  std::string tok;
  while (fields >> tok) {
    char* end = nullptr;
    const double x = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0') throw Error(where, "not a number: '" + tok + "'");
    if (!std::isfinite(x)) throw Error(where, "non-finite value");
    v.push_back(x);
  }
  return v;
}

std::vector<TumPose> ReadTumTrajectory(std::istream& in, const std::string& source_name) {
  std::vector<TumPose> poses;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = source_name + ":" + std::to_string(line_no);
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    // Some exporters separate with commas; accept them as whitespace.
    for (char& ch : line) {
      if (ch == ',' || ch == '\t' || ch == '\r') ch = ' ';
    }
    const std::vector<double> v = ParseNumberFields(line, where);
    if (v.size() != 8) {
      throw Error(where, "expected 8 values (timestamp tx ty tz qx qy qz qw), got " +
                             std::to_string(v.size()));
    }
    TumPose p;
    p.time_s = v[0];
    p.center = {v[1], v[2], v[3]};
    p.world_from_cam = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
    if (std::abs(p.world_from_cam.norm() - 1.0) > 1e-3) {
      throw Error(where, "quaternion is not unit length");
    }
    p.world_from_cam = CanonicalQuaternion(p.world_from_cam);
    if (!poses.empty() && p.time_s <= poses.back().time_s) {
      throw Error(where, "timestamp is not increasing");
    }
    poses.push_back(p);
  }
  if (poses.empty()) throw Error(source_name, "no poses");
  return poses;
}

std::vector<TumPose> ReadTumTrajectoryFile(const std::string& path) {
  InputFile in(path);
  return ReadTumTrajectory(in.stream(), path);
}

void WriteTumTrajectory(const CameraPath& path, std::ostream& out) {
  out << "# timestamp tx ty tz qx qy qz qw (camera-to-world; hapcine camera axes: "
         "-Z forward, +Y up)\n";
  for (const auto& f : path.frames) {
    const std::string bad = ValidateCameraFrame(f);
    if (!bad.empty()) throw Error("camera path", "frame " + std::to_string(f.frame) + ": " + bad);
    const Eigen::Quaterniond q = CanonicalQuaternion(f.world_from_cam);
    out << FormatFixed(f.time_s, 6) << ' ' << FormatDouble(f.center.x()) << ' '
        << FormatDouble(f.center.y()) << ' ' << FormatDouble(f.center.z()) << ' '
        << FormatDouble(q.x()) << ' ' << FormatDouble(q.y()) << ' ' << FormatDouble(q.z())
        << ' ' << FormatDouble(q.w()) << '\n';
  }
}

void WriteTumTrajectoryFile(const CameraPath& path, const std::string& file) {
  AtomicFile out(file);
  WriteTumTrajectory(path, out.stream());
  out.Commit();
}

CameraPath CameraPathFromTum(const std::vector<TumPose>& poses, double fov_deg) {
  CameraPath path;
  int index = 0;
  for (const auto& p : poses) {
    CameraFrame f;
    f.frame = index++;
    f.time_s = p.time_s;
    f.center = p.center;
    f.world_from_cam = p.world_from_cam;
    f.fov_deg = fov_deg;
    path.frames.push_back(f);
  }
  return path;
}

}  // namespace hapcine
