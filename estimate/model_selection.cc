#include "estimate/model_selection.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/statistics.h"
#include "estimate/two_view_estimators.h"
#include "estimate/two_view_geometry.h"

namespace hapcine {

void TwoViewOptions::Check() const {
  if (!(noise_floor > 0)) throw UsageError("two-view noise_floor must be > 0");
  if (!(inlier_threshold > 0)) throw UsageError("two-view inlier_threshold must be > 0");
  if (min_correspondences < 8) throw UsageError("two-view min_correspondences must be >= 8");
  if (!(focal_search_range > 1)) throw UsageError("two-view focal_search_range must be > 1");
  ransac.Check();
}

double Gric(const std::vector<double>& sq, double sigma, int d, int k) {
  constexpr double r = 4, lambda3 = 2;
  const double n = static_cast<double>(sq.size());
  const double cap = lambda3 * (r - d);
  const double s2 = sigma * sigma;
  double sum = 0;
  for (double e2 : sq) sum += std::isfinite(e2) ? std::min(e2 / s2, cap) : cap;
  return sum + std::log(r) * d * n + std::log(r * std::max(n, 1.0)) * k;
}

namespace {

std::vector<Eigen::Vector2d> Scaled(const std::vector<Eigen::Vector2d>& u, double inv_f) {
  std::vector<Eigen::Vector2d> c(u.size());
  for (size_t i = 0; i < u.size(); ++i) c[i] = u[i] * inv_f;
  return c;
}

template <typename T>
std::vector<T> Select(const std::vector<T>& v, const std::vector<char>& mask) {
  std::vector<T> out;
  for (size_t i = 0; i < v.size(); ++i)
    if (mask[i]) out.push_back(v[i]);
  return out;
}

std::vector<char> Mask(const std::vector<double>& sq, double thr) {
  std::vector<char> m(sq.size());
  for (size_t i = 0; i < sq.size(); ++i) m[i] = std::isfinite(sq[i]) && sq[i] <= thr * thr;
  return m;
}

// Squared distance to a homography-type manifold: half the transfer error.
void RotationResiduals(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                       const Eigen::Matrix3d& R, double f1, double f2, std::vector<double>* out) {
  out->resize(u1.size());
  for (size_t i = 0; i < u1.size(); ++i) {
    const Eigen::Vector3d p = R * (u1[i] / f1).homogeneous();
    (*out)[i] = p.z() > 1e-9 ? 0.5 * (f2 * p.hnormalized() - u2[i]).squaredNorm()
                             : std::numeric_limits<double>::infinity();
  }
}

}  // namespace

TwoViewResult SelectTwoViewModel(const std::vector<Eigen::Vector2d>& u1,
                                 const std::vector<Eigen::Vector2d>& u2, double f1,
                                 const TwoViewOptions& options) {
  TwoViewResult result;
  const int n = static_cast<int>(u1.size());
  result.num_points = n;
  result.f1 = result.f2 = f1;
  if (n != static_cast<int>(u2.size()) || n < options.min_correspondences || !(f1 > 0)) return result;
  double thr = options.inlier_threshold;
  RansacOptions ro = options.ransac;

  // --- general: essential matrix at the current focal (also gives sigma).
  // The inlier threshold grows with the measured noise (4 sigma), so noisy
  // tracks are not thrown away as outliers.
  const auto c1 = Scaled(u1, 1 / f1), c2 = Scaled(u2, 1 / f1);
  RansacReport<Eigen::Matrix3d> ess;
  std::vector<double> e_ess(n, std::numeric_limits<double>::infinity());
  double sigma = options.noise_floor;
  for (int pass = 0; pass < 2; ++pass) {
    ro.max_error = thr / f1;
    ess = Ransac<EssentialEstimator>(c1, c2, ro);
    if (ess.success) {
      EssentialEstimator::Residuals(c1, c2, ess.model, &e_ess);
      for (double& e : e_ess) e *= f1 * f1;  // calibrated -> normalised units
    }
    std::vector<double> inlier_abs;
    for (int i = 0; i < n; ++i)
      if (ess.success && ess.inlier_mask[i]) inlier_abs.push_back(std::sqrt(e_ess[i]));
    sigma = std::max(options.noise_floor, 1.4826 * Median(inlier_abs, 0.0));
    if (4 * sigma <= thr) break;
    thr = 4 * sigma;
  }
  result.sigma = sigma;

  // --- static
  std::vector<double> e_static(n);
  for (int i = 0; i < n; ++i) e_static[i] = 0.5 * (u2[i] - u1[i]).squaredNorm();

  // --- zoom
  ro.max_error = thr;
  const auto zoom = Ransac<ZoomEstimator>(u1, u2, ro);
  const double s = zoom.success ? zoom.model : 1.0;
  std::vector<double> e_zoom(n);
  for (int i = 0; i < n; ++i) e_zoom[i] = 0.5 * (u2[i] - s * u1[i]).squaredNorm();

  // --- rotation (shared focal, refined): RANSAC at f, refit f on the inliers, repeat.
  double f_rot = f1;
  Eigen::Matrix3d R_rot = Eigen::Matrix3d::Identity();
  std::vector<double> e_rot(n, std::numeric_limits<double>::infinity());
  for (int pass = 0; pass < 2; ++pass) {
    ro.max_error = thr / f_rot;
    const auto rot = Ransac<RotationEstimator>(Scaled(u1, 1 / f_rot), Scaled(u2, 1 / f_rot), ro);
    if (!rot.success) break;
    const auto in1 = Select(u1, rot.inlier_mask), in2 = Select(u2, rot.inlier_mask);
    double f_new;
    Eigen::Matrix3d R_new;
    FitRotationAndFocal(in1, in2, f_rot, options.focal_search_range, &f_new, &R_new);
    f_rot = f_new;
    R_rot = R_new;
    RotationResiduals(u1, u2, R_rot, f_rot, f_rot, &e_rot);
  }

  // --- rotation + zoom: view 1 at the given or at the rotation model's
  // focal (the latter is biased when the focal changed), view 2 free.
  double f1_rz = f_rot, f2_rz = f_rot;
  Eigen::Matrix3d R_rz = R_rot;
  std::vector<double> e_rz(n, std::numeric_limits<double>::infinity());
  double best_rz_cost = std::numeric_limits<double>::infinity();
  // Also a coarse ladder around f1: while the focal is still the prior (50
  // deg), a telephoto pan with zoom (true focal 4x the prior) has no
  // rotation+zoom fit near f1 and f_rot (a constant-focal fit, biased by
  // the zoom); the general homography then wins with a spurious translation.
  std::vector<double> f1_tries = {f1};
  if (f_rot != f1) f1_tries.push_back(f_rot);
  for (double k : {0.5, 2.0, 4.0}) f1_tries.push_back(f1 * k);
  for (double f1_try : f1_tries) {
    ro.max_error = thr;
    const auto rz = Ransac<RotationZoomEstimator>(Scaled(u1, 1 / f1_try), u2, ro);
    if (!rz.success) continue;
    const auto in1 = Select(u1, rz.inlier_mask), in2 = Select(u2, rz.inlier_mask);
    double f2;
    Eigen::Matrix3d R;
    FitRotationZoom(in1, in2, f1_try, rz.model.f2, 1.2, &f2, &R);
    std::vector<double> e;
    RotationResiduals(u1, u2, R, f1_try, f2, &e);
    const double cost = Gric(e, std::max(options.noise_floor, 1e-12), 2, 5);
    if (cost < best_rz_cost) {
      best_rz_cost = cost;
      f1_rz = f1_try;
      f2_rz = f2;
      R_rz = R;
      e_rz = e;
    }
  }

  // --- general homography (planar scene with translation)
  ro.max_error = thr;
  const auto hom = Ransac<HomographyEstimator>(u1, u2, ro);
  std::vector<double> e_hom(n, std::numeric_limits<double>::infinity());
  if (hom.success) {
    HomographyEstimator::Residuals(u1, u2, hom.model, &e_hom);
    for (double& e : e_hom) e *= 0.5;
  }

  result.gric[kCandStatic] = Gric(e_static, sigma, 2, 0);
  result.gric[kCandZoom] = zoom.success ? Gric(e_zoom, sigma, 2, 1) : HUGE_VAL;
  result.gric[kCandRotation] = Gric(e_rot, sigma, 2, 4);
  result.gric[kCandRotationZoom] = Gric(e_rz, sigma, 2, 5);
  result.gric[kCandEssential] = ess.success ? Gric(e_ess, sigma, 3, 5) : HUGE_VAL;
  result.gric[kCandHomography] = hom.success ? Gric(e_hom, sigma, 2, 8) : HUGE_VAL;
  int best = 0;
  for (int c = 1; c < kNumCandidates; ++c)
    if (result.gric[c] < result.gric[best]) best = c;

  // The essential matrix must also give a valid relative pose; otherwise
  // fall back to the best homography-type model.
  Eigen::Matrix3d R_ess = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_ess = Eigen::Vector3d::Zero();
  const bool pose_ok = ess.success && DecomposeEssential(ess.model, Select(c1, ess.inlier_mask),
                                                         Select(c2, ess.inlier_mask), &R_ess, &t_ess);
  if ((best == kCandEssential || best == kCandHomography) && !pose_ok) {
    best = kCandStatic;
    for (int c = 1; c <= kCandRotationZoom; ++c)
      if (result.gric[c] < result.gric[best]) best = c;
  }

  const std::vector<double>* e_best = &e_static;
  switch (best) {
    case kCandStatic:
      result.model = MotionModel::kStatic;
      break;
    case kCandZoom:
      result.model = MotionModel::kZoom;
      result.f2 = f1 * s;
      e_best = &e_zoom;
      break;
    case kCandRotation:
      result.model = MotionModel::kRotation;
      result.cam2_from_cam1 = R_rot;
      result.f1 = result.f2 = f_rot;
      e_best = &e_rot;
      break;
    case kCandRotationZoom:
      result.model = MotionModel::kRotationZoom;
      result.cam2_from_cam1 = R_rz;
      result.f1 = f1_rz;
      result.f2 = f2_rz;
      e_best = &e_rz;
      break;
    default:
      result.model = MotionModel::kGeneral;
      result.cam2_from_cam1 = R_ess;
      result.translation = t_ess;
      e_best = best == kCandEssential ? &e_ess : &e_hom;
      break;
  }
  // Inliers at the RANSAC threshold (on half-squared transfer errors for H-type).
  const double thr_best = best == kCandEssential ? thr : thr / std::sqrt(2.0);
  result.inliers = Mask(*e_best, thr_best);
  result.num_inliers = static_cast<int>(std::count(result.inliers.begin(), result.inliers.end(), 1));
  result.valid = true;
  return result;
}

}  // namespace hapcine
