#include "estimate/geometry/model_selection.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>

#include "core/error.h"
#include "core/statistics.h"
#include "estimate/geometry/two_view_estimators.h"
#include "estimate/geometry/two_view_geometry.h"

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

// RANSAC with `base`'s settings at the inlier threshold `max_error`.
RansacOptions At(const RansacOptions& base, double max_error) {
  RansacOptions ro = base;
  ro.max_error = max_error;
  return ro;
}

// Every candidate model's fit to the correspondences: its parameters and the
// squared distance of each correspondence to its manifold (normalised
// units; +inf where it has none).
struct ModelFits {
  int n = 0;
  double thr = 0;    // the inlier threshold, grown with the measured noise
  double sigma = 0;  // the noise, from the essential matrix's inliers
  std::vector<Eigen::Vector2d> c1, c2;  // calibrated at f1
  RansacReport<Eigen::Matrix3d> ess;
  std::vector<double> e_ess, e_static, e_zoom, e_rot, e_rz, e_hom;
  bool zoom_ok = false, hom_ok = false;
  double s = 1;  // zoom factor
  double f_rot = 1;
  Eigen::Matrix3d R_rot = Eigen::Matrix3d::Identity();
  double f1_rz = 1, f2_rz = 1;
  Eigen::Matrix3d R_rz = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
};

// The essential matrix by the five-point solver (OpenCV's Nister RANSAC) on
// calibrated coordinates, scored with our residuals at `thr_cal`. Why: the
// eight-point solver ignores the essential constraints until it projects its
// linear solution; under a long lens the view is nearly affine, the linear
// system has a near two-dimensional null space, and the projected minimal
// solutions are noise: on a 23 degree orbit step at an 11 degree FOV no
// eight-point sample found eight inliers. The five-point solver imposes the
// constraints inside the minimal problem, so it holds in that regime.
RansacReport<Eigen::Matrix3d> FivePointEssential(const std::vector<Eigen::Vector2d>& c1,
                                                 const std::vector<Eigen::Vector2d>& c2,
                                                 const RansacOptions& ro) {
  RansacReport<Eigen::Matrix3d> report;
  const int n = static_cast<int>(c1.size());
  if (n < 5) return report;
  std::vector<cv::Point2d> p1(n), p2(n);
  for (int i = 0; i < n; ++i) {
    p1[i] = cv::Point2d(c1[i].x(), c1[i].y());
    p2[i] = cv::Point2d(c2[i].x(), c2[i].y());
  }
  cv::Mat E = cv::findEssentialMat(p1, p2, 1.0, cv::Point2d(0, 0), cv::RANSAC, ro.confidence, ro.max_error);
  if (E.rows < 3 || E.cols != 3) return report;
  Eigen::Matrix3d model;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) model(r, c) = E.at<double>(r, c);
  if (!model.allFinite()) return report;
  std::vector<double> res;
  EssentialEstimator::Residuals(c1, c2, model, &res);
  report.inlier_mask = Mask(res, ro.max_error);
  report.num_inliers = static_cast<int>(std::count(report.inlier_mask.begin(), report.inlier_mask.end(), 1));
  report.model = model;
  report.success = report.num_inliers >= EssentialEstimator::kMinNumSamples;
  return report;
}

// General: essential matrix at the current focal (also gives sigma). The
// inlier threshold grows with the measured noise (4 sigma), so noisy tracks
// are not thrown away as outliers.
void FitEssential(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2, double f1,
                  const TwoViewOptions& options, ModelFits* m) {
  const int n = m->n;
  m->c1 = Scaled(u1, 1 / f1);
  m->c2 = Scaled(u2, 1 / f1);
  m->e_ess.assign(n, std::numeric_limits<double>::infinity());
  m->sigma = options.noise_floor;
  for (int pass = 0; pass < 2; ++pass) {
    m->ess = Ransac<EssentialEstimator>(m->c1, m->c2, At(options.ransac, m->thr / f1));
    // The five-point solver only where the eight-point one found nothing, so
    // every interval it already fits keeps its fit (and its cost).
    if (!m->ess.success) m->ess = FivePointEssential(m->c1, m->c2, At(options.ransac, m->thr / f1));
    if (m->ess.success) {
      EssentialEstimator::Residuals(m->c1, m->c2, m->ess.model, &m->e_ess);
      for (double& e : m->e_ess) e *= f1 * f1;  // calibrated -> normalised units
    }
    std::vector<double> inlier_abs;
    for (int i = 0; i < n; ++i)
      if (m->ess.success && m->ess.inlier_mask[i]) inlier_abs.push_back(std::sqrt(m->e_ess[i]));
    m->sigma = std::max(options.noise_floor, 1.4826 * Median(inlier_abs, 0.0));
    if (4 * m->sigma <= m->thr) break;
    m->thr = 4 * m->sigma;
  }
}

void FitStaticAndZoom(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                      const TwoViewOptions& options, ModelFits* m) {
  const int n = m->n;
  m->e_static.resize(n);
  for (int i = 0; i < n; ++i) m->e_static[i] = 0.5 * (u2[i] - u1[i]).squaredNorm();
  const auto zoom = Ransac<ZoomEstimator>(u1, u2, At(options.ransac, m->thr));
  m->zoom_ok = zoom.success;
  m->s = zoom.success ? zoom.model : 1.0;
  m->e_zoom.resize(n);
  for (int i = 0; i < n; ++i) m->e_zoom[i] = 0.5 * (u2[i] - m->s * u1[i]).squaredNorm();
}

// Rotation (shared focal, refined): RANSAC at f, refit f on the inliers, repeat.
void FitRotation(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2, double f1,
                 const TwoViewOptions& options, ModelFits* m) {
  m->f_rot = f1;
  m->e_rot.assign(m->n, std::numeric_limits<double>::infinity());
  for (int pass = 0; pass < 2; ++pass) {
    const auto rot = Ransac<RotationEstimator>(Scaled(u1, 1 / m->f_rot), Scaled(u2, 1 / m->f_rot),
                                               At(options.ransac, m->thr / m->f_rot));
    if (!rot.success) break;
    const auto in1 = Select(u1, rot.inlier_mask), in2 = Select(u2, rot.inlier_mask);
    double f_new;
    Eigen::Matrix3d R_new;
    FitRotationAndFocal(in1, in2, m->f_rot, options.focal_search_range, &f_new, &R_new);
    m->f_rot = f_new;
    m->R_rot = R_new;
    RotationResiduals(u1, u2, m->R_rot, m->f_rot, m->f_rot, &m->e_rot);
  }
}

// Rotation + zoom: view 1 at the given or at the rotation model's focal (the
// latter is biased when the focal changed), view 2 free. Also a coarse
// ladder around f1: while the focal is still the prior (50 deg), a
// telephoto pan with zoom (true focal 4x the prior) has no rotation+zoom fit
// near f1 and f_rot (a constant-focal fit, biased by the zoom); the general
// homography then wins with a spurious translation.
void FitRotationZoomModel(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                          double f1, const TwoViewOptions& options, ModelFits* m) {
  m->f1_rz = m->f2_rz = m->f_rot;
  m->R_rz = m->R_rot;
  m->e_rz.assign(m->n, std::numeric_limits<double>::infinity());
  double best_rz_cost = std::numeric_limits<double>::infinity();
  std::vector<double> f1_tries = {f1};
  if (m->f_rot != f1) f1_tries.push_back(m->f_rot);
  for (double k : {0.5, 2.0, 4.0}) f1_tries.push_back(f1 * k);
  for (double f1_try : f1_tries) {
    const auto rz = Ransac<RotationZoomEstimator>(Scaled(u1, 1 / f1_try), u2, At(options.ransac, m->thr));
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
      m->f1_rz = f1_try;
      m->f2_rz = f2;
      m->R_rz = R;
      m->e_rz = e;
    }
  }
}

// General homography (planar scene with translation).
void FitHomography(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                   const TwoViewOptions& options, ModelFits* m) {
  const auto hom = Ransac<HomographyEstimator>(u1, u2, At(options.ransac, m->thr));
  m->hom_ok = hom.success;
  m->H = hom.model;
  m->e_hom.assign(m->n, std::numeric_limits<double>::infinity());
  if (hom.success) {
    HomographyEstimator::Residuals(u1, u2, hom.model, &m->e_hom);
    for (double& e : m->e_hom) e *= 0.5;
  }
}

// GRIC of every candidate, with one isotropic sigma.
void ScoreIsotropic(const ModelFits& m, TwoViewResult* result) {
  result->gric[kCandStatic] = Gric(m.e_static, m.sigma, 2, 0);
  result->gric[kCandZoom] = m.zoom_ok ? Gric(m.e_zoom, m.sigma, 2, 1) : HUGE_VAL;
  result->gric[kCandRotation] = Gric(m.e_rot, m.sigma, 2, 4);
  result->gric[kCandRotationZoom] = Gric(m.e_rz, m.sigma, 2, 5);
  result->gric[kCandEssential] = m.ess.success ? Gric(m.e_ess, m.sigma, 3, 5) : HUGE_VAL;
  result->gric[kCandHomography] = m.hom_ok ? Gric(m.e_hom, m.sigma, 2, 8) : HUGE_VAL;
}

// The lowest GRIC; the essential matrix must also give a valid relative
// pose, otherwise the best homography-type model.
int ChooseCandidate(const std::array<double, kNumCandidates>& gric, bool pose_ok) {
  int best = 0;
  for (int c = 1; c < kNumCandidates; ++c)
    if (gric[c] < gric[best]) best = c;
  if ((best == kCandEssential || best == kCandHomography) && !pose_ok) {
    best = kCandStatic;
    for (int c = 1; c <= kCandRotationZoom; ++c)
      if (gric[c] < gric[best]) best = c;
  }
  return best;
}

// The chosen candidate's model, pose and focal lengths into `result`; its
// residuals.
const std::vector<double>& TakeCandidate(int best, const ModelFits& m, double f1, const Eigen::Matrix3d& R_ess,
                                         const Eigen::Vector3d& t_ess, TwoViewResult* result) {
  switch (best) {
    case kCandStatic:
      result->model = MotionModel::kStatic;
      return m.e_static;
    case kCandZoom:
      result->model = MotionModel::kZoom;
      result->f2 = f1 * m.s;
      return m.e_zoom;
    case kCandRotation:
      result->model = MotionModel::kRotation;
      result->cam2_from_cam1 = m.R_rot;
      result->f1 = result->f2 = m.f_rot;
      return m.e_rot;
    case kCandRotationZoom:
      result->model = MotionModel::kRotationZoom;
      result->cam2_from_cam1 = m.R_rz;
      result->f1 = m.f1_rz;
      result->f2 = m.f2_rz;
      return m.e_rz;
    default:
      result->model = MotionModel::kGeneral;
      result->cam2_from_cam1 = R_ess;
      result->translation = t_ess;
      return best == kCandEssential ? m.e_ess : m.e_hom;
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
  ModelFits m;
  m.n = n;
  m.thr = options.inlier_threshold;
  FitEssential(u1, u2, f1, options, &m);
  result.sigma = m.sigma;
  FitStaticAndZoom(u1, u2, options, &m);
  FitRotation(u1, u2, f1, options, &m);
  FitRotationZoomModel(u1, u2, f1, options, &m);
  FitHomography(u1, u2, options, &m);
  ScoreIsotropic(m, &result);
  Eigen::Matrix3d R_ess = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_ess = Eigen::Vector3d::Zero();
  const bool pose_ok = m.ess.success && DecomposeEssential(m.ess.model, Select(m.c1, m.ess.inlier_mask),
                                                           Select(m.c2, m.ess.inlier_mask), &R_ess, &t_ess);
  const int best = ChooseCandidate(result.gric, pose_ok);
  const std::vector<double>& e_best = TakeCandidate(best, m, f1, R_ess, t_ess, &result);
  // Inliers at the RANSAC threshold (on half-squared transfer errors for H-type).
  const double thr_best = best == kCandEssential ? m.thr : m.thr / std::sqrt(2.0);
  result.inliers = Mask(e_best, thr_best);
  result.num_inliers = static_cast<int>(std::count(result.inliers.begin(), result.inliers.end(), 1));
  result.valid = true;
  return result;
}

}  // namespace hapcine
