#pragma once
// Keeping a whole film inside the actuators' workspaces, as motion
// simulators do ("classical washout"):
//  1. High-pass: camera signals pass two cascaded first-order high-passes
//     (order 2, the default; order 1 = one section) with time constant
//     tau_s before the model scales them, so sustained offsets (a camera
//     that moved and then stopped, a long traveling) decay back to the
//     centre. Order 2: a held offset decays as (1 - t/tau) exp(-t/tau)
//     (a 13.5 % undershoot at 2 tau), a constant camera velocity v gives
//     v t exp(-t/tau): it peaks at t = tau and returns to 0. Order 1: a held
//     offset decays as exp(-t/tau) but a constant velocity leaves a plateau
//     v*tau. The onset of every movement, which is what the body perceives,
//     passes unchanged.
//  2. Cut transitions: at a shot cut the output crossfades from the value
//     held at the end of the previous shot to the new shot's signal over
//     cut_ramp_s with a C2 "smootherstep" weight: a convex combination, so it
//     never leaves the box both ends are in, and it never jumps.
//  3. Rate limit: no coordinate moves by more than max_speed_m_s / rate_hz
//     per sample (the step stays between the previous output and the
//     target, so it also stays in the box).
//  4. Clamp: every coordinate to +-clamp_half_m. The scaling keeps the
//     models within +-usable_half_m, so this should never fire; the number
//     of clamped samples is reported in the track metadata.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/haptic_track.h"

namespace hapcine {

using ActuatorFrame = std::array<Eigen::Vector3d, kNumActuators>;

struct WashoutOptions {
  bool high_pass = true;       // step 1 (--no-washout turns it off)
  double tau_s = 4.0;          // high-pass time constant, seconds
  int order = 2;               // 1 or 2 cascaded first-order sections
  double cut_ramp_s = 0.5;     // crossfade at a shot cut, seconds
  double max_speed_m_s = 0.5;  // per-coordinate speed limit
  void Check() const;          // throws UsageError
};

// High-pass filters x (sampled at possibly irregular times) in place with
// `order` cascaded first-order sections y_n = a_n (y_{n-1} + x_n - x_{n-1}),
// a_n = tau / (tau + dt_n). The filter starts at rest with x[0] as its
// reference: y[0] = 0 (the signals are relative to the shot start anyway).
void HighPassInPlace(const std::vector<double>& time_s, std::vector<double>* x, double tau_s,
                     int order);

// C2 smooth step 6u^5 - 15u^4 + 10u^3 on [0, 1], clamped outside.
double SmootherStep(double u);

// Step 2: for each cut time c, samples with c <= t < c + ramp_s become
// (1 - w) * held + w * value, held = the output just before c.
// Steps 2-4 take a model's frames or, the same, a track's samples (positions
// only): a long film's track is shaped in place, with no second copy.
void ApplyCutTransitions(const std::vector<double>& time_s, const std::vector<double>& cut_times_s,
                         double ramp_s, std::vector<ActuatorFrame>* frames);
void ApplyCutTransitions(const std::vector<double>& time_s, const std::vector<double>& cut_times_s,
                         double ramp_s, std::vector<HapticSample>* samples);

// Step 3; returns the number of samples that were limited.
int LimitVelocity(double max_step_m, std::vector<ActuatorFrame>* frames);
int LimitVelocity(double max_step_m, std::vector<HapticSample>* samples);

// Step 4; returns the number of samples with at least one clamped coordinate.
int ClampToWorkspace(double clamp_half_m, std::vector<ActuatorFrame>* frames);
int ClampToWorkspace(double clamp_half_m, std::vector<HapticSample>* samples);

}  // namespace hapcine
