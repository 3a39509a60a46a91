#pragma once
// The camera path file (*.camera.csv): see docs/formats.md ("Camera path specification"),
// which this code implements exactly. Pose is camera-to-world
// (`world_from_cam`), rotation stored as a scalar-first unit quaternion with
// qw >= 0, positions in metres or in "median scene depth" units.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/optional_name.h"

namespace hapcine {

// Small fields first: the frame packs into 128 bytes (a 10-million-row path
// is held in memory by the readers of it).
struct CameraFrame {
  int frame = 0;        // 0-based decoded frame index
  std::optional<int> shot;  // optional column
  OptionalName model;   // optional column: static, zoom, rotation, rotation+zoom, general
  double time_s = 0;    // presentation time, seconds
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // camera centre c in world
  Eigen::Quaterniond world_from_cam = Eigen::Quaterniond::Identity();
  double fov_deg = 0;   // horizontal field of view of the decoded frame
  // Optional columns (written when set; also shot and model above).
  std::optional<double> focal_px;
  std::optional<double> confidence;  // [0, 1]
  std::optional<int> source_frame;   // optional column: the image's number in its file name
};

// The `model` of a frame the estimator could not place (docs/formats.md): its
// pose is a placeholder (the last placed pose), its confidence 0; readers must
// not treat it as motion.
inline constexpr const char* kLostModel = "lost";
inline bool IsLost(const CameraFrame& f) { return f.model == kLostModel; }

struct CameraPath {
  // "# key=value" lines; width, height, fps are the conventional keys.
  std::map<std::string, std::string> metadata;
  std::vector<CameraFrame> frames;

  // Convenience accessors for metadata (0 when missing or malformed).
  int width() const;
  int height() const;
  double fps() const;
};

// Reads and validates a camera path. Throws hapcine::Error with
// "<source>:<line>: <reason>" on: missing or wrong header, missing columns,
// unparsable or non-finite numbers, truncated lines, non-increasing time,
// non-unit quaternions (|q| off by more than 1e-3), fov outside (0, 180),
// confidence outside [0, 1]. Unknown extra columns are ignored.
CameraPath ReadCameraPath(std::istream& in, const std::string& source_name);
CameraPath ReadCameraPathFile(const std::string& path);

// Writes the required columns, then the optional columns that any frame sets
// (focal_px, pan_deg, tilt_deg, roll_deg, shot, model, confidence). Quaternions
// are normalised and given qw >= 0. Throws Error on non-finite values.
void WriteCameraPath(const CameraPath& path, std::ostream& out);
// Atomic: temporary file, then rename.
void WriteCameraPathFile(const CameraPath& path, const std::string& file);

// Sanity check used by readers and writers; returns "" when valid, else the reason.
std::string ValidateCameraFrame(const CameraFrame& f);

}  // namespace hapcine
