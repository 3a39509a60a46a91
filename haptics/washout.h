#pragma once
// Keeping a whole film inside the actuators' workspaces without false cues.
//  1. Washout, one of three modes:
//     - adaptive (the default): a shot that the per-shot scaling fits
//       without giving up more than half of its gain (its motion over the
//       whole shot is less than twice its largest motion within any
//       window_s) gets no washout at all: Equations 2-6 with the paper's
//       per-shot scaling. A longer drift gets the gain its window_s motion
//       deserves and a return to centre in actuator space
//       (ApplyReturnToCentre): a return speed that follows the distance to
//       the centre (time constant chosen per shot, the slowest that fits),
//       changes with an acceleration below the vestibular threshold
//       (return_accel_m_s2), and never opposes a coordinate that is moving:
//       it returns in still moments and at cuts only.
//     - highpass (the classical washout of motion simulators; it gives
//       false cues: a camera that keeps moving one way is felt going back):
//       the camera signals pass two cascaded first-order high-passes
//       (order 2; order 1 = one section) with time constant tau_s before
//       the model scales them. Order 2: a held offset decays as
//       (1 - t/tau) exp(-t/tau), a constant camera velocity v gives
//       v t exp(-t/tau): it peaks at t = tau and returns to 0 while the
//       camera still moves. Order 1 leaves a plateau v*tau.
//     - off: Equations 2-6 with the per-shot scaling, whatever the shot.
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
#include <string>
#include <vector>

#include "core/haptic_track.h"

namespace hapcine {

using ActuatorFrame = std::array<Eigen::Vector3d, kNumActuators>;

enum class WashoutMode { kOff, kHighPass, kAdaptive };
const char* WashoutModeName(WashoutMode m);  // "off", "highpass", "adaptive"
WashoutMode WashoutModeFromName(const std::string& name);  // throws UsageError

struct WashoutOptions {
  WashoutMode mode = WashoutMode::kAdaptive;  // step 1 (--no-washout = kOff)
  // highpass mode:
  double tau_s = 4.0;          // high-pass time constant, seconds
  int order = 2;               // 1 or 2 cascaded first-order sections
  // adaptive mode:
  double window_s = 7.0;       // span scaling alone fits (the paper's clip length)
  double min_gain = 2.0;       // washout only where it at least doubles a shot's gain
  // Largest acceleration of the return: below the 0.01 m/s^2 that
  // Richerson et al. 2006 (J NeuroEng Rehabil 3:2) found for detecting
  // 2-16 mm whole-body displacements, and the 0.057 m/s^2 of Benson et al.
  // 1986 (Aviat Space Environ Med 57:1088) for 3 s horizontal movements.
  double return_accel_m_s2 = 0.01;
  // A coordinate slower than this fraction of the shot's fastest one is still.
  double still_fraction = 0.02;
  double cut_ramp_s = 0.5;     // crossfade at a shot cut, seconds
  double max_speed_m_s = 0.5;  // per-coordinate speed limit
  bool HighPass() const { return mode == WashoutMode::kHighPass; }
  void Check() const;          // throws UsageError
};

// High-pass filters x (sampled at possibly irregular times) in place with
// `order` cascaded first-order sections y_n = a_n (y_{n-1} + x_n - x_{n-1}),
// a_n = tau / (tau + dt_n). The filter starts at rest with x[0] as its
// reference: y[0] = 0 (the signals are relative to the shot start anyway).
void HighPassInPlace(const std::vector<double>& time_s, std::vector<double>* x, double tau_s,
                     int order);

// Adaptive mode. The speed below which a coordinate of these frames counts
// as still: still_fraction of the fastest coordinate, at least 0.1 mm/s.
double StillSpeed(const std::vector<double>& time_s, const std::vector<ActuatorFrame>& frames,
                  double still_fraction);

// Largest |coordinate| over the frames, and the largest range (max - min)
// of one coordinate within any window of window_s seconds.
double PeakCoordinate(const std::vector<ActuatorFrame>& frames);
double LargestWindowRange(const std::vector<double>& time_s,
                          const std::vector<ActuatorFrame>& frames, double window_s);

// Return to centre, per coordinate, in place: p_n = p_{n-1} + (f_n - f_{n-1})
// - r_n dt, the return speed r heading for p / tau_s, changing by at most
// accel_m_s2 * dt per frame, and never larger than the coordinate's own
// speed against it while the coordinate moves (faster than still_speed): so
// the output never moves against the input, and returns where it is still.
void ApplyReturnToCentre(const std::vector<double>& time_s, double still_speed, double tau_s,
                         double accel_m_s2, std::vector<ActuatorFrame>* frames);

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
// Step 3 on rows that need not be evenly spaced (a semantic track's 1 kHz
// rows between its stored-rate rows): no coordinate moves faster than
// max_speed_m_s from one row to the next; a row 1/rate_hz after the previous
// one moves at most max_speed_m_s / rate_hz, exactly as LimitVelocity.
// `limited_rows` (optional) gets one flag per row.
int LimitSpeed(double max_speed_m_s, double rate_hz, std::vector<HapticSample>* samples,
               std::vector<char>* limited_rows = nullptr);

// Step 4; returns the number of samples with at least one clamped coordinate.
int ClampToWorkspace(double clamp_half_m, std::vector<ActuatorFrame>* frames);
int ClampToWorkspace(double clamp_half_m, std::vector<HapticSample>* samples);

}  // namespace hapcine
