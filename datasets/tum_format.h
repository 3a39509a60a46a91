#pragma once
// The TUM RGB-D trajectory format, for evo and the other SLAM tools:
// one pose per line, `timestamp tx ty tz qx qy qz qw`, space-separated,
// `#` comment lines allowed. The pose is camera-to-world (the camera centre
// and the rotation world_from_cam), which is what the camera path stores, so
// the conversion copies numbers: the quaternion moves from scalar-first
// (camera path) to scalar-last (TUM). Camera axes stay the project's
// (OpenGL: -Z forward, +Y up); evo's APE/RPE do not depend on the camera axes
// as long as both files use the same ones.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "core/camera_path.h"

namespace hapcine {

struct TumPose {
  double time_s = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Quaterniond world_from_cam = Eigen::Quaterniond::Identity();
};

// The whitespace-separated numbers of one line of a text trajectory (TUM,
// KITTI, Nuke .chan); an empty vector for a blank line. Throws Error(where)
// for a field that is not a finite number.
std::vector<double> ParseNumberFields(const std::string& line, const std::string& where);

// Throws hapcine::Error("<source>:<line>", reason) on lines that do not hold
// exactly 8 finite numbers, non-unit quaternions (|q| off by > 1e-3) and
// non-increasing timestamps. Empty input is an error.
std::vector<TumPose> ReadTumTrajectory(std::istream& in, const std::string& source_name);
std::vector<TumPose> ReadTumTrajectoryFile(const std::string& path);

// One line per frame of the camera path, full double precision. A header
// comment names the format. Atomic file variant.
void WriteTumTrajectory(const CameraPath& path, std::ostream& out);
void WriteTumTrajectoryFile(const CameraPath& path, const std::string& file);

// A camera path from TUM poses: frames numbered 0.. in file order, every
// frame given `fov_deg` (TUM carries no intrinsics).
CameraPath CameraPathFromTum(const std::vector<TumPose>& poses, double fov_deg);

}  // namespace hapcine
