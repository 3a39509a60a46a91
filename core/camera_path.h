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

#include "core/compact_values.h"
#include "core/optional_name.h"

namespace hapcine {

// A frame is held in 80 bytes (128 with plain doubles, std::optional and an
// aligned Eigen quaternion): readers hold a whole path, up to 10 million rows,
// and must peak under twice the file's size; the shortest valid row is about
// 42 bytes (docs/benchmarks.md, "Memory of the readers"). Doubles where the
// digits matter (time, centre); the rotation as its three smallest quaternion
// coefficients (exact to 1e-16); the intrinsics and confidence at single
// precision (files print them as the shortest text of that float, which reads
// back to the same value); compact optionals (core/compact_values.h).
struct CameraFrame {
  double time_s = 0;    // presentation time, seconds
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // camera centre c in world
  CompactQuaternion world_from_cam;  // identity; reads as an Eigen::Quaterniond
  StoredFloat fov_deg;  // horizontal field of view of the decoded frame (0 until set)
  // Optional columns (written when set).
  OptionalFloat focal_px;
  OptionalFloat confidence;  // [0, 1]
  int frame = 0;        // 0-based decoded frame index
  OptionalInt shot;     // holds any int but INT32_MIN
  OptionalName model;   // static, zoom, rotation, rotation+zoom, general, lost
};
// Why 80: the reader's peak is the frames plus a few MB, and the benchmark's
// minimal rows (`frame,time,0,0,z,1,0,0,0,60`) are 42 bytes, so 80 keeps it
// under twice the file (bench/memory.sh).
static_assert(sizeof(CameraFrame) <= 80, "a camera frame must stay within 80 bytes");

// The `model` of a frame the estimator could not place (docs/formats.md): its
// pose is a placeholder (the last placed pose), its confidence 0; readers must
// not treat it as motion.
inline constexpr const char* kLostModel = "lost";
inline bool IsLost(const CameraFrame& f) { return f.model == kLostModel; }

struct CameraPath {
  // "# key=value" lines; width, height, fps are the conventional keys.
  std::map<std::string, std::string> metadata;
  std::vector<CameraFrame> frames;
  // The optional `source_frame` column (an image sequence's number of each
  // frame's image): empty when absent, else one per frame (unset: an empty
  // cell). Kept beside the frames, not in them: a frame's 80 bytes are spent.
  std::vector<OptionalInt> source_frames;

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
