#pragma once
// One radial distortion coefficient, estimated from the tracks by model
// selection, and the undistortion of track points.
//
// Model (the ffmpeg `lenscorrection` filter's, so that its k1 is ours):
//   p_undistorted = c + (p - c) (1 + k1 r^2),  r = |p - c| / (half the diagonal)
// with c the image centre (the principal point stays there). Barrel
// distortion (straight lines bow outwards) is k1 > 0 in this convention.
//
// Estimation (EstimateRadialDistortion): frame pairs of the first frames of
// a shot, each far enough apart (median track motion >= 3 % of the width).
// For each candidate k1 every pair's tracks are undistorted and a homography
// refitted (least squares on the inliers RANSAC found at k1 = 0; sigma fixed
// from k1 = 0); the pair costs the better by GRIC of that homography and the
// fundamental matrix of the tracks as they are. Radial distortion is not
// projective, so a homography does not absorb it: k1 is measured on the
// pairs a homography explains (pan, roll, zoom, plane). F's 7 degrees of
// freedom absorb a distortion in either direction (rotation, near-planar
// scenes, forward motion's radial epipolar lines), so parallax pairs do not
// vote; and a distorted pan, which F fits better at k1 = 0, is given back to
// the homography at its k1. k1 is kept only if it lowers the summed GRIC by
// more than the price of one more parameter, ln(4 n) (n correspondences in
// all), lowers the cost of at least 3/4 of the pairs that measure it (a lens
// is the same in every pair), with at least 3 such pairs, moves the
// picture's corner by more than the noise, and is not at the end of the
// search range; otherwise 0.

#include <Eigen/Core>
#include <vector>

#include "extract/tracks.h"

namespace hapcine {

// A k1 that moves the picture's corner by under 0.5 % of the half-diagonal
// is no finding: the scatter of one view pair's best k1 on pinhole footage
// (measured +-0.009 on a rendered tilt). 0.0115 (a 50 deg lens at synth's
// k1 = -0.04) already costs a tilt 0.75 deg of rotation (docs/estimate.md).
constexpr double kMinLensK1 = 0.005;
// The tracks' noise floor, px at the reference width (the estimator's,
// window_solver.h).
constexpr double kLensNoiseFloorPx = 0.25;

// The undistorted position of `px` (decoded pixels, OpenCV centre
// convention) in a width x height picture.
Eigen::Vector2d UndistortRadial(const Eigen::Vector2d& px, double k1, int width, int height);

// Undistorts every point of `tracks` in place (k1 = 0: untouched).
void UndistortTracks(double k1, int width, int height, FrameTracks* tracks);

struct RadialDistortionEstimate {
  double k1 = 0;           // 0 unless it paid for itself
  double best_k1 = 0;      // the best candidate, kept or not
  double gric_gain = 0;    // GRIC(0) - GRIC(best_k1)
  double penalty = 0;      // what one more parameter costs, ln(4 n)
  int pairs = 0;           // frame pairs used
  int correspondences = 0;
};

// From the first frames of a shot (consecutive FrameTracks of one shot).
// Searches k1 in [-max_abs_k1, max_abs_k1].
RadialDistortionEstimate EstimateRadialDistortion(const std::vector<FrameTracks>& frames,
                                                  int width, int height, double max_abs_k1 = 0.25);

}  // namespace hapcine
