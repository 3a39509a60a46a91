#pragma once
// KLT drift with track age: an observation's noise grows with the frames
// its track has been followed since the point's first observation in the
// window (docs/estimate.md, "Track drift weights").
//
// A KLT track re-matches a patch frame to frame, so its position error is
// a random walk: each step adds an independent error, and an observation
// `age` frames after the anchor observation is off by a variance
// s0^2 + age q^2 (s0: the matching noise of one frame). Both are estimated
// from the window's own residuals (least squares of e^2 on age); where the
// growth is significant the observations are weighted by 1 / sigma(age).

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// e^2 = s0_sq + q_sq * age, fitted by least squares.
struct DriftFit {
  double s0_sq = 0;     // the noise variance at age 0 (normalised units^2)
  double q_sq = 0;      // its growth per frame of age
  double t_slope = 0;   // q_sq over its standard error (ordinary least squares)
  int observations = 0;
  // The growth is there: q_sq > 0 at kDriftMinT standard errors, s0_sq > 0.
  bool significant = false;
};

// The slope's t at which the growth counts as measured: 3 standard errors,
// a one-sided false alarm under 0.2 % where the noise does not grow. (The
// residuals of one track are correlated, so the formal error is a lower
// bound; 3 leaves room for that.)
constexpr double kDriftMinT = 3.0;

// Each observation's age in frames: its keyframe's frame position
// (`keyframe_pos[camera]`) minus that of the earliest observation of its
// point in `observations`.
std::vector<int> ObservationAges(const std::vector<BaObservation>& observations, const std::vector<int>& keyframe_pos);

// The fit of squared residuals `errors` (normalised units; non-finite ones
// skipped) against `ages`.
DriftFit FitDrift(const std::vector<double>& errors, const std::vector<int>& ages);

// Sets each observation's noise_scale to sigma(age) / s0 =
// sqrt(1 + age q_sq / s0_sq) where the fit is significant; returns whether
// it did (else every noise_scale is left as it was).
bool ApplyDriftWeights(const DriftFit& fit, const std::vector<int>& ages, std::vector<BaObservation>* observations);

}  // namespace hapcine
