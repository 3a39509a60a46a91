#pragma once
// One radial distortion coefficient measured over many views: a small
// bundle adjustment of a solved window (its keyframe cameras, its rigid
// points and their observations) with k1 as one more parameter, and model
// selection on it. Two views cannot separate k1 from parallax (a
// fundamental matrix absorbs it); a rigid point seen from many positions
// can: its rays must meet at one point, and radial distortion bends them by
// an amount that depends on where in the picture each view sees it.
//
// k1 is in lens_distortion.h's convention (ffmpeg lenscorrection: r in
// half-diagonals, barrel k1 > 0). Both solves also free one factor on the
// focal, so that k1 pays only for what a focal change cannot explain (a
// focal held at a wrong prior bends a rotation's tracks radially too); the
// factor is not used: the window decided the focal (docs/estimate.md
// "Lens distortion").

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// A window as its solve left it, observations in the estimator's normalised
// coordinates (pixels - image centre) / width, distorted as tracked.
struct SolvedWindow {
  std::vector<BaCamera> cameras;
  std::vector<BaPoint> points;
  std::vector<BaObservation> observations;
  bool use_depth = false;        // points have depths (some interval translates)
  bool focal_observable = false; // the window solved the focal
};

struct LensBundleEstimate {
  double k1 = 0;          // 0 unless it paid for itself
  double best_k1 = 0;     // the adjustment's k1, kept or not
  double chi2_gain = 0;   // capped chi2 at k1 = 0 minus at best_k1 (units of sigma^2)
  double penalty = 0;     // what it had to exceed: max(ln N (BIC, N residuals), 2 sigma's 4)
  double sigma_k1 = 0;    // |best_k1| / sqrt(chi2_gain): the profile's curvature
  double noise_px = 0;    // the residuals' robust sigma, pixels of the decoded frame
  // sigma_k1 x sqrt(observations per point): a track's errors over its
  // keyframes are one drift, not independent draws, so a point is one
  // measurement (what windows are compared with, EstimateK1InWindows).
  double track_sigma_k1 = 0;
  int observations = 0;
  int points = 0;         // points with observations
  bool solved = false;
};

// Adjusts the window's rotations, centres, points and focal factor with k1
// fixed at 0 and with k1 free in [-max_abs_k1, max_abs_k1]; keeps k1 when the capped chi2
// gain exceeds max(ln N, 4) (BIC's price and |k1| > 2 sigma), |k1| is at
// least 0.005 and it is not at the end of the range.
LensBundleEstimate EstimateK1InWindow(const SolvedWindow& window, int width, int height,
                                      double max_abs_k1 = 0.25);

// k1 measured independently in several windows of one shot and pooled
// (inverse variance). A lens is a property of the whole shot and comes back
// in every window within its standard error; a k1 that absorbs something
// else (drift, a wrong focal, parallax) changes with the window's motion.
struct LensAgreement {
  double k1 = 0;            // the pooled k1 where kept, else 0
  double pooled_k1 = 0;     // inverse-variance mean of the measuring windows
  double sigma = 0;         // its standard error
  double spread_chi2 = 0;   // the windows' k1 about the pooled one, in their sigmas
  double spread_limit = 0;  // what it must stay under (chi2 95 % with n - 1 dof)
  int measuring = 0;        // windows whose k1 has a standard error
  int significant = 0;      // windows whose k1 pays for itself (chi2 gain > penalty)
  bool same_sign = false;   // every measuring window's k1 has the pooled one's sign
  std::vector<LensBundleEstimate> windows;
};

// Keeps the pooled k1 when at least 2 windows pay for their own k1 (each
// window's chi2 gain over its penalty, EstimateK1InWindow), every window
// with a standard error agrees (track_sigma_k1: spread_chi2 <= spread_limit,
// same sign) and the pooled k1 is at least 0.005 and inside the range. A
// lens comes back in every window; one window's k1 alone is not kept (no
// other window confirmed it). Windows are measured in order until too few
// are left to reach two that pay (`windows` holds those measured).
LensAgreement EstimateK1InWindows(const std::vector<SolvedWindow>& windows, int width, int height,
                                  double max_abs_k1 = 0.25);

}  // namespace hapcine
