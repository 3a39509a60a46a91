#pragma once
// A motion platform: which of its six degrees of freedom move, how far and
// how fast each may go, the cueing parameters, and for a Stewart platform
// the joint geometry (docs/haptics.md, "Motion platforms").
//
// Pose of the platform (moving frame relative to its home pose), in the seat
// frame of the haptic track (+X right, +Y up, +Z backward; screen at -Z):
//   [0] sway  x  metres, + to the right
//   [1] heave y  metres, + up
//   [2] surge z  metres, + backward (forward is -z)
//   [3] pitch rx radians about +X, + front up
//   [4] yaw   ry radians about +Y, + turning left
//   [5] roll  rz radians about +Z, + right side up
// Orientation R = Rx(pitch) Ry(yaw) Rz(roll), the order of Equation 5, so a
// camera's tilt, pan and roll map one to one onto pitch, yaw and roll.
//
// JSON (`hapcine haptics CAM --seat platform.json`), recognised by
// "type": "platform"; HapSeat files have no "type" key:
//   "name": text, "rate_hz": output rate (10..10000, default 100),
//   "dofs": {"heave": {"position": .., "velocity": .., "acceleration": ..}, ...}
//       the DOFs that move (others stay at 0); limits are symmetric (+-),
//       metres, m/s, m/s^2 for sway/heave/surge, degrees, deg/s, deg/s^2 for
//       pitch/yaw/roll;
//   "stewart": {"base_anchors_m": 6 x [x,y,z], "top_anchors_m": 6 x [x,y,z],
//       "min_leg_m": .., "max_leg_m": ..}  (optional; see stewart.h)
//   "cueing": {...} overrides of CueingParams (keys as the fields below,
//       angles in degrees: "tilt_max_deg", "tilt_rate_deg_s", "return_rate_deg_s",
//       "return_accel_deg_s2"...).

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

namespace hapcine {

enum class Dof { kSway = 0, kHeave = 1, kSurge = 2, kPitch = 3, kYaw = 4, kRoll = 5 };
constexpr int kNumDofs = 6;
const char* DofName(Dof d);  // "sway", "heave", "surge", "pitch", "yaw", "roll"
inline bool IsRotation(int dof) { return dof >= 3; }

using PlatformPose = Eigen::Matrix<double, 6, 1>;

struct DofLimits {
  double position = 0;      // |pose| <= position (m or rad)
  double velocity = 0;      // m/s or rad/s
  double acceleration = 0;  // m/s^2 or rad/s^2
};

// Classical motion cueing parameters (platform/motion_cueing.h). Angles in
// radians here, degrees in the JSON.
struct CueingParams {
  // Share of each DOF's position limit (and of the leg stroke) the scaling
  // aims for; the rest is the safety clamp's margin.
  double usable_fraction = 0.9;
  // Translation scale cap: a camera motion of this many path units (10 % of
  // the median scene depth for estimated paths) fills the usable range, and
  // no smaller motion is amplified more (the HapSeat's rule).
  double fill_motion_u = 0.1;
  // Returns to home outside cuts stay below the vestibular thresholds:
  // otoliths ~0.05 m/s^2 (Benson et al. 1986: 0.057-0.063 m/s^2 horizontal),
  // semicircular canals ~3 deg/s (the tilt-rate limit of Reid & Nahon 1985,
  // Groen & Bles 2004).
  double return_accel_m_s2 = 0.05;
  double return_speed_m_s = 0.05;
  double return_rate_rad_s = 0.0523598775598;      // 3 deg/s
  double return_accel_rad_s2 = 0.0523598775598;    // 3 deg/s^2
  // Tilt coordination: low-passed specific force (two first-order sections
  // of tilt_lowpass_s / 2) rendered as pitch/roll so gravity gives a
  // sustained acceleration, at most tilt_max (and a quarter of the usable
  // pitch or roll) and turning at most tilt_rate (3 deg/s, below the canals'
  // threshold).
  double tilt_max_rad = 0.0872664625997;   // 5 deg
  double tilt_rate_rad_s = 0.0523598775598;  // 3 deg/s
  double tilt_lowpass_s = 1.0;
  // Camera acceleration (path units/s^2) -> specific force (m/s^2).
  double specific_force_gain = 1.0;
  // At a cut the eye expects a jump: returns there may use half of each
  // DOF's velocity and acceleration limits for this long.
  double cut_ramp_s = 0.5;
  // Below this speed a camera signal counts as still (returns may proceed);
  // above it the platform never moves against it. Platform units after
  // scaling: m/s for translations, rad/s for rotations.
  double still_speed_m_s = 0.0002;
  double still_rate_rad_s = 0.000349065850399;  // 0.02 deg/s
  void Check() const;  // throws UsageError
};

struct StewartGeometry {
  // Lower joints in the base frame = the seat frame with its origin at the
  // moving frame's home position (so the base anchors have y < 0).
  std::array<Eigen::Vector3d, 6> base_m;
  // Upper joints in the moving frame (origin = centre of rotation).
  std::array<Eigen::Vector3d, 6> top_m;
  double min_leg_m = 0;
  double max_leg_m = 0;
};

struct PlatformConfig {
  std::string name = "platform";
  double rate_hz = 100;
  bool enabled[kNumDofs] = {false, false, false, false, false, false};
  DofLimits limits[kNumDofs];
  std::optional<StewartGeometry> stewart;
  CueingParams cueing;
  int NumEnabled() const;
  // Throws UsageError: at least one DOF, limits finite and > 0 (position
  // <= 1 m or 60 deg), rate in [10, 10000], cueing parameters in range, and
  // a Stewart platform's legs at home inside the usable stroke.
  void Check() const;
};

// True when the JSON text is an object with "type": "platform".
bool IsPlatformJson(const std::string& text);
// True when the file reads as JSON with "type": "platform" (false for a
// HapSeat file, an unreadable file or invalid JSON: the HapSeat reader then
// reports the error).
bool IsPlatformFile(const std::string& path);
PlatformConfig ParsePlatformJson(const std::string& text, const std::string& source_name);
PlatformConfig LoadPlatformFile(const std::string& path);
std::string PlatformConfigToJson(const PlatformConfig& config);

}  // namespace hapcine
