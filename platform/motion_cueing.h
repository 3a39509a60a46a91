#pragma once
// Classical motion cueing for a motion platform, driven by the cinematic
// model's camera signals (haptics/camera_signals.h: Equation 1's
// parameters relative to each shot's first frame, lost frames eased to
// rest). Per degree of freedom (platform_config.h):
//
//   sway, heave, surge  <- k * (x_c, y_c, z_c - gamma_c)   (Eq. 4 and 6: a
//                          zoom-in is a forward move, a dolly zoom cancels)
//   pitch, yaw, roll    <- m * (phi_c, theta_c, psi_c)     (Eq. 5's angles)
//
// i.e. the platform reproduces the scaled camera motion (the double integral
// of the scaled specific force, and the integral of the scaled angular
// rate). Classical washout high-passes these; a linear high-pass moves the
// platform back while the camera still moves forward (a false cue), so here
// the low-frequency part is removed by a return to home that
//  - never moves against a camera signal while it moves (its speed over
//    0.25 s above the still threshold: CueingParams::still_speed_m_s /
//    still_rate_rad_s, or 2 % of the shot's fastest speed when lower): it
//    may then only go the camera's way,
//  - runs in still moments below the vestibular thresholds (0.05 m/s^2,
//    3 deg/s: CueingParams),
//  - and at a cut, for cut_ramp_s, faster (half the DOF's limits): the
//    picture jumps anyway.
// Tilt coordination: the specific force of the camera's horizontal
// acceleration (camera acceleration x specific_force_gain), low-passed, is
// rendered by tilting the seat so that gravity pushes the same way
// (surge acceleration forward -> pitch front up, sway acceleration right ->
// roll right side up), at most tilt_max, turning at most tilt_rate (3 deg/s,
// below the semicircular canals' threshold, Reid & Nahon 1985).
//
// Scaling per shot (the HapSeat's pre-processing pass): the largest k (one
// for all translations, keeping the direction; at most usable / fill_motion_u)
// and m (<= 1: never more than the camera's own angles) such that the
// simulated poses, returns included, stay within usable_fraction of each
// DOF's position limit (rotations: less the tilt budget, a quarter of the
// usable pitch and roll); for a Stewart platform both then shrink together
// until every pose of the shot keeps its legs inside the stroke less a
// margin. Where shots meet, a pose still outside is scaled back towards
// home. Every sample then passes PlatformSafety (platform_safety.h).

#include "core/camera_path.h"
#include "platform/platform_config.h"
#include "platform/platform_track.h"

namespace hapcine {

struct PlatformOptions {
  std::string model = "cinematic";  // "cinematic" or "none" (stays home)
  double reference_depth_u = 0;     // as CinematicOptions (0 = per shot, automatic)
  double rate_hz = 0;               // 0 = the config's rate_hz
  std::string source;               // the track's `source`
  void Check() const;               // throws UsageError
};

// Per shot: translation metres per path unit (k) and rotation gain (m).
struct PlatformShotScale {
  double translation_m_per_u = 0;
  double rotation_gain = 0;
};

// The platform track of a camera path (validated by the caller as for
// haptic tracks). Metadata: clamped_samples, stroke_limited_samples,
// nonfinite_samples, and the cueing thresholds used.
PlatformTrack MakePlatformTrack(const CameraPath& path, const PlatformConfig& config,
                                const PlatformOptions& options,
                                std::vector<PlatformShotScale>* scales = nullptr);

}  // namespace hapcine
