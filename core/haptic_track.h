#pragma once
// The haptic track file (*.haptic.csv): see docs/formats.md ("Haptic track specification").
// For each instant, the displacement G_A -> G'_A of each HapSeat actuator
// from the centre of its own workspace, in metres, in the seat frame
// (+X right, +Y up, +Z backward). Rows at a fixed rate (# rate_hz).
//
// This header is what the 1 kHz loop depends on: Eigen only, no OpenCV/Ceres.

#include <Eigen/Core>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/optional_name.h"

namespace hapcine {

enum class Actuator { kHead = 0, kLeft = 1, kRight = 2 };
constexpr int kNumActuators = 3;
const char* ActuatorName(Actuator a);  // "head", "left", "right"

struct HapticSample {
  double time_s = 0;
  // Indexed by Actuator: [0] head, [1] left hand, [2] right hand. Metres.
  Eigen::Vector3d pos_m[kNumActuators] = {Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero()};
  std::optional<int> shot;
  OptionalName effect;  // 2 bytes: a handful of distinct effects over millions of rows
};

// How a player reads a track between its rows ("# interpolation=" in the
// file; a track without the line is linear, as every track before it).
//   linear:         straight lines between rows (1 kHz tracks).
//   monotone_cubic: cubic Hermite with three-point (Catmull-Rom) slopes,
//                   limited per coordinate (Fritsch-Carlson) so that the curve
//                   never leaves the range of the two rows around it: no
//                   overshoot past a step, a clamp or the workspace. Exact on
//                   constants and lines, and on quadratics where they are monotone.
enum class TrackInterpolation { kLinear, kMonotoneCubic };
const char* TrackInterpolationName(TrackInterpolation i);  // "linear", "monotone_cubic"
// The interpolation a new track stored at rate_hz asks for: monotone cubic
// below the player's 1 kHz loop, linear at or above it (played as before).
TrackInterpolation InterpolationForRate(double rate_hz);

struct HapticTrack {
  double rate_hz = 1000;
  TrackInterpolation interpolation = TrackInterpolation::kLinear;
  std::string model = "none";  // cinematic, semantic, random, none
  std::string source;          // the video or camera path it was made from
  std::map<std::string, std::string> metadata;  // other "# key=value" lines
  std::vector<HapticSample> samples;

  double duration_s() const {
    return samples.empty() ? 0 : samples.back().time_s - samples.front().time_s;
  }
  // The positions at time t, interpolated as `interpolation` says (clamped
  // to the ends). Allocation-free: safe to call from the 1 kHz tick. `hint`
  // speeds up monotone access.
  void Sample(double t, Eigen::Vector3d out[kNumActuators],
              size_t* hint = nullptr) const;
};

// Throws hapcine::Error "<source>:<line>: <reason>" on a wrong header, missing
// metadata (rate_hz, model, source), non-finite values, non-increasing time,
// truncated lines, |position| > 1 m (absurd for a 0.1 m workspace), an
// unknown interpolation.
HapticTrack ReadHapticTrack(std::istream& in, const std::string& source_name);
HapticTrack ReadHapticTrackFile(const std::string& path);
void WriteHapticTrack(const HapticTrack& track, std::ostream& out);
void WriteHapticTrackFile(const HapticTrack& track, const std::string& file);

}  // namespace hapcine
