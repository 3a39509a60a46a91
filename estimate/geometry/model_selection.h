#pragma once
// Which motion explains two views? Fits every candidate model robustly and
// picks the one with the lowest GRIC (Torr's Geometric Robust Information
// Criterion):
//
//   GRIC = sum_i min(e_i^2 / sigma^2, lambda3 (r - d)) + lambda1 d n + lambda2 k
//   lambda1 = ln r, lambda2 = ln(r n), lambda3 = 2, r = 4 (two 2-D views)
//
// e_i is the distance of correspondence i to the model's manifold, n the
// number of correspondences, d the manifold's dimension, k the model's
// parameter count:
//   static         H = I                       d = 2, k = 0
//   zoom           x2 = s x1                   d = 2, k = 1
//   rotation       H = K R K^-1 (f fitted)     d = 2, k = 4
//   rotation+zoom  H = K2 R K1^-1              d = 2, k = 5
//   general        essential matrix (f given)  d = 3, k = 5
//   general        general homography (plane)  d = 2, k = 8
// The homography family has d = 2 (a point in view 1 fixes its match), the
// essential matrix d = 3 (a match may slide along its epipolar line), so
// parallax — depth-dependent motion that no homography explains — is what
// makes "general" win; a pan of a far or planar scene stays "rotation".
// For homography-type models e_i^2 is half the squared transfer error (the
// first-order distance in the 4-D joint space), for the essential matrix
// the squared Sampson distance.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "estimate/geometry/motion_model.h"
#include "estimate/geometry/ransac.h"
#include "estimate/geometry/reference_width.h"

namespace hapcine {

struct TwoViewOptions {
  double noise_floor = 0.25 / kReferenceWidthPx;      // lower bound on sigma, normalised units
  double inlier_threshold = 1.5 / kReferenceWidthPx;  // RANSAC inlier threshold, normalised units
  int min_correspondences = 12;           // fewer: result.valid = false
  double focal_search_range = 2.0;        // rotation model searches f in [f1 / r, f1 * r]
  RansacOptions ransac;                   // max_error is set per model from inlier_threshold
  void Check() const;                     // throws UsageError
};

enum TwoViewCandidate { kCandStatic = 0, kCandZoom, kCandRotation, kCandRotationZoom, kCandEssential, kCandHomography, kNumCandidates };

struct TwoViewResult {
  bool valid = false;                     // false: too few correspondences
  MotionModel model = MotionModel::kStatic;
  Eigen::Matrix3d cam2_from_cam1 = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // unit (X2 = R X1 + t) for general, else 0
  double f1 = 1, f2 = 1;                  // focal lengths (normalised) under the chosen model
  double sigma = 0;                       // noise level used, normalised units
  int num_points = 0;
  int num_inliers = 0;                    // of the chosen model
  std::vector<char> inliers;              // of the chosen model
  std::array<double, kNumCandidates> gric{};
};

// GRIC of a set of squared residuals (see above).
double Gric(const std::vector<double>& squared_residuals, double sigma, int d, int k);

// u1, u2: matched normalised coordinates; f1: current focal estimate of view 1.
TwoViewResult SelectTwoViewModel(const std::vector<Eigen::Vector2d>& u1,
                                 const std::vector<Eigen::Vector2d>& u2, double f1,
                                 const TwoViewOptions& options);

}  // namespace hapcine
