#pragma once
// The Cinematic model (section 4.3, Equations 2-6): the user feels the
// movement of the camera. For each actuator A,
//   G_A -> G'_A = f(T, R_A, F) = (|T| T + |R_A| R_A + |F| F) / (|T| + |R_A| + |F|)
//   T   = diag(kx, ky, kz) (x_c, y_c, z_c)                           (Eq. 4)
//   R_A = (Rx(mx phi) Ry(my theta) Rz(mz psi) - I) vec(G G_A)        (Eq. 5)
//   F   = (0, 0, sz * gamma_c)                                       (Eq. 6)
// with f = 0 when all three vanish. Camera parameters are relative to the
// first frame of the shot and expressed in the seat frame (camera_signals.h).
// gamma_c = -zoom_forward_u: a zoom-in (narrowing FOV) is a FORWARD (-Z)
// movement. Because zoom_forward_u is an equivalent forward distance in the
// same units as the camera position, sz = kz makes a dolly zoom (Vertigo)
// give F = -T exactly, so f = 0: no movement, as the paper states.
//
// Scaling (the paper's pre-processing pass), per shot by default:
//   k = kx = ky = kz = sz = min(max_translation_gain, usable / P),
//       P = max over the shot of |x|, |y|, |z|, |gamma| (after washout);
//       one gain for all axes keeps the direction of motion.
//   m = mx = my = mz = the largest m <= max_rotation_gain such that no
//       coordinate of any R_A exceeds usable over the shot (searched).
// Since f is a convex combination of T, R_A, F, every coordinate of f then
// stays within +-usable. Because f averages T, R_A and F, it can stay below
// the range when they point different ways (a crane tilting down to keep its
// subject framed); k, sz and m are then raised together by the largest gain
// (<= 3, within the caps) that keeps every coordinate of f within +-usable,
// so the actuators use their range and never saturate, while the
// cancellation of opposing vectors (Vertigo) is not amplified back. The caps
// keep estimator noise in a still shot from being blown up to the full
// workspace.

#include <vector>

#include "core/camera_path.h"
#include "haptics/camera_signals.h"
#include "haptics/seat_geometry.h"
#include "haptics/washout.h"

namespace hapcine {

struct CinematicScale {
  double kx = 0, ky = 0, kz = 0;  // Eq. 4, metres of seat per path unit
  double mx = 0, my = 0, mz = 0;  // Eq. 5, multipliers of the camera angles
  double sz = 0;                  // Eq. 6, metres per path unit of gamma
  // Adaptive washout: time constant of the shot's return to centre
  // (ApplyReturnToCentre); 0 = none, the plain Equations 2-6.
  double return_tau_s = 0;
};

// Scaling factors per shot (index = order of the shot in the path). A path
// with more shots than entries reuses the last entry, so factors computed
// from one path can be applied to another (e.g. ground truth vs estimate).
struct CinematicScaling {
  std::vector<CinematicScale> per_shot;
  const CinematicScale& ForShot(size_t i) const;
};

struct CinematicOptions {
  // Distance D of the subject whose magnification defines gamma, in path
  // units; 0 = automatic per shot (ShotReferenceDepth: a dolly zoom's own
  // subject distance, else metadata subject_distance_m / reference_depth,
  // else 1 = the median depth of estimated paths).
  double reference_depth_u = 0;
  // Cap on k = sz, metres per path unit: 0.45 fills +-0.045 m with a motion
  // of 10 % of the median scene depth, and no smaller motion is amplified more.
  double max_translation_gain = 0.45;
  // Cap on m: rotations are never exaggerated beyond the camera's own.
  double max_rotation_gain = 1.0;
  // One set of factors for the whole film (minimum over shots) instead of
  // one per shot.
  bool per_film_scaling = false;
  void Check() const;  // throws UsageError
};

// Equations 2-6 at one instant. Returns G_A G'_A for head, left, right.
ActuatorFrame CinematicDisplacement(const Eigen::Vector3d& position_u, double tilt_rad,
                                    double pan_rad, double roll_rad, double zoom_forward_u,
                                    const CinematicScale& scale, const SeatGeometry& seat);

// Per-shot signals (after the washout high-pass in highpass mode).
std::vector<CameraSignals> CinematicShotSignals(const CameraPath& path,
                                                const std::vector<ShotRange>& shots,
                                                const CinematicOptions& options,
                                                const WashoutOptions& washout);

// The pre-processing pass. In adaptive washout mode a shot whose motion the
// per-shot scaling cannot fit without losing more than washout.min_gain
// gets a larger gain and a return to centre (AdaptiveReturnForShot).
CinematicScaling ComputeCinematicScaling(const CameraPath& path, const SeatGeometry& seat,
                                         const CinematicOptions& options,
                                         const WashoutOptions& washout);

// Displacements per camera frame (aligned with path.frames).
std::vector<ActuatorFrame> CinematicFrames(const CameraPath& path, const SeatGeometry& seat,
                                           const CinematicOptions& options,
                                           const WashoutOptions& washout,
                                           const CinematicScaling& scaling);

}  // namespace hapcine
