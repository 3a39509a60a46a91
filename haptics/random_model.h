#pragma once
// The Random feedback of the user study (section 5.1): low-pass filtered
// white noise, cutoff 0.5 Hz, not synchronised with the video.
//
// Nine independent channels (3 actuators x 3 axes) of seeded Gaussian white
// noise at the output rate pass a 2nd-order Butterworth low-pass (bilinear
// transform) run forward then backward (zero phase). The combined response
// |H|^2 is -3 dB at cutoff_hz, the paper's F_c (each pass is designed at
// ZeroPhaseSectionCutoffHz, 1.25 x higher: one section at the cutoff would
// put the combined -3 dB at 0.80 x the cutoff); 4th-order roll-off.
// The result is scaled so that the largest coordinate of the whole track is
// exactly usable_half_m (the same "use the workspace, never saturate"
// rule as the cinematic model) and faded in/out over fade_s at both ends so
// the track starts and ends at the centre.

#include <cstdint>
#include <vector>

#include "haptics/seat_geometry.h"
#include "haptics/washout.h"

namespace hapcine {

struct RandomOptions {
  uint64_t seed = 1;       // same seed -> same track
  double cutoff_hz = 0.5;  // the paper's F_c
  double fade_s = 1.0;     // fade in/out at the ends of the track
  void Check() const;      // throws UsageError
};

// One value per time in time_s (uniformly sampled at seat.rate_hz).
std::vector<ActuatorFrame> RandomFrames(size_t num_samples, double rate_hz,
                                        const SeatGeometry& seat, const RandomOptions& options);

// Cutoff of each pass such that the two together are -3 dB at cutoff_hz
// (needs cutoff_hz < rate_hz / 2).
double ZeroPhaseSectionCutoffHz(double cutoff_hz, double rate_hz);

// Zero-phase 2nd-order Butterworth low-pass (-3 dB at cutoff_hz), exposed for tests.
std::vector<double> ButterworthLowPassZeroPhase(const std::vector<double>& x, double cutoff_hz,
                                                double rate_hz);

}  // namespace hapcine
