#pragma once
// Two-view estimators in the RANSAC "estimator concept" (see ransac.h).
// Conventions: OpenCV camera frame inside the estimator (x right, y down,
// z forward). "Normalised" image coordinates u = (pixel - principal point) / s
// with s a nominal size (the decoded width), so a focal length f in these
// units is f_px / s. "Calibrated" coordinates are u / f, i.e. the bearing
// (x, y, 1). Every relative rotation here is cam2_from_cam1: X2 = R X1 (+ t).
//
// Only estimation lives here; maths on finished models (decomposition,
// triangulation, focal refinement) lives in two_view_geometry.h.

#include <Eigen/Core>
#include <vector>

namespace hapcine {

// x2 = s * x1 about the principal point (a pure zoom). Normalised coordinates.
struct ZoomEstimator {
  using X_t = Eigen::Vector2d;
  using Y_t = Eigen::Vector2d;
  using M_t = double;  // scale s = f2 / f1
  static constexpr int kMinNumSamples = 1;
  static std::vector<M_t> Estimate(const std::vector<X_t>& x1, const std::vector<Y_t>& x2);
  static void Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2, const M_t& s,
                        std::vector<double>* squared_residuals);
};

// Pure rotation with known focal lengths: H = K2 R K1^-1 on calibrated
// coordinates of both views. Kabsch on bearings (2 points minimal).
struct RotationEstimator {
  using X_t = Eigen::Vector2d;  // calibrated, view 1
  using Y_t = Eigen::Vector2d;  // calibrated, view 2
  using M_t = Eigen::Matrix3d;  // cam2_from_cam1
  static constexpr int kMinNumSamples = 2;
  static std::vector<M_t> Estimate(const std::vector<X_t>& b1, const std::vector<Y_t>& b2);
  static void Residuals(const std::vector<X_t>& b1, const std::vector<Y_t>& b2, const M_t& R,
                        std::vector<double>* squared_residuals);
};

// Rotation with a focal change: view 1 calibrated (f1 known), view 2 in
// normalised coordinates with unknown focal f2. Two points: the angle between
// two rays is preserved by a rotation, which gives a quadratic in f2^2; then
// Kabsch. Residuals are in view 2's normalised units.
struct RotationZoom {
  Eigen::Matrix3d cam2_from_cam1 = Eigen::Matrix3d::Identity();
  double f2 = 1;
};
struct RotationZoomEstimator {
  using X_t = Eigen::Vector2d;  // calibrated, view 1
  using Y_t = Eigen::Vector2d;  // normalised, view 2
  using M_t = RotationZoom;
  static constexpr int kMinNumSamples = 2;
  static std::vector<M_t> Estimate(const std::vector<X_t>& b1, const std::vector<Y_t>& u2);
  static void Residuals(const std::vector<X_t>& b1, const std::vector<Y_t>& u2, const M_t& m,
                        std::vector<double>* squared_residuals);
};

// General 8-dof homography x2 ~ H x1 (any coordinates): normalised DLT.
struct HomographyEstimator {
  using X_t = Eigen::Vector2d;
  using Y_t = Eigen::Vector2d;
  using M_t = Eigen::Matrix3d;
  static constexpr int kMinNumSamples = 4;
  static std::vector<M_t> Estimate(const std::vector<X_t>& x1, const std::vector<Y_t>& x2);
  // Squared transfer error in view 2.
  static void Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2, const M_t& H,
                        std::vector<double>* squared_residuals);
};

// Essential matrix on calibrated coordinates (x2^T E x1 = 0): normalised
// eight-point algorithm, projected onto the essential manifold
// (singular values 1, 1, 0). Residual: squared Sampson distance.
struct EssentialEstimator {
  using X_t = Eigen::Vector2d;
  using Y_t = Eigen::Vector2d;
  using M_t = Eigen::Matrix3d;
  static constexpr int kMinNumSamples = 8;
  static std::vector<M_t> Estimate(const std::vector<X_t>& x1, const std::vector<Y_t>& x2);
  static void Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2, const M_t& E,
                        std::vector<double>* squared_residuals);
};

}  // namespace hapcine
