#include "estimate/geometry/motion_hypotheses.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "estimate/geometry/two_view_estimators.h"

namespace hapcine {

void MoverOptions::Check() const {
  if (!(border_radius > 0 && border_radius < 1)) throw UsageError("mover border radius must be in (0, 1)");
}

double BorderRadius(const Eigen::Vector2d& u, double half_height) {
  return std::max(std::abs(u.x()) / 0.5, std::abs(u.y()) / half_height);
}

std::vector<double> TwoViewResiduals(const TwoViewResult& r, const std::vector<Eigen::Vector2d>& u1,
                                     const std::vector<Eigen::Vector2d>& u2) {
  const size_t n = u1.size();
  std::vector<double> e(n, std::numeric_limits<double>::infinity());
  if (HasTranslation(r.model)) {
    // X2 = R X1 + t: E = [t]x R on calibrated coordinates at f1.
    Eigen::Matrix3d tx;
    const Eigen::Vector3d& t = r.translation;
    tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
    std::vector<Eigen::Vector2d> c1(n), c2(n);
    for (size_t i = 0; i < n; ++i) {
      c1[i] = u1[i] / r.f1;
      c2[i] = u2[i] / r.f1;
    }
    EssentialEstimator::Residuals(c1, c2, tx * r.cam2_from_cam1, &e);
    for (double& v : e) v *= r.f1 * r.f1;
    return e;
  }
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = r.cam2_from_cam1 * (u1[i] / r.f1).homogeneous();
    if (p.z() > 1e-9) e[i] = 0.5 * (r.f2 * p.hnormalized() - u2[i]).squaredNorm();
  }
  return e;
}

std::vector<char> TwoViewInliers(const TwoViewResult& r, const std::vector<double>& sq, double threshold) {
  // Homography-type residuals are half the squared transfer error.
  const double limit = HasTranslation(r.model) ? threshold * threshold : 0.5 * threshold * threshold;
  std::vector<char> in(sq.size());
  for (size_t i = 0; i < sq.size(); ++i) in[i] = std::isfinite(sq[i]) && sq[i] <= limit;
  return in;
}

double TwoViewThreshold(const TwoViewResult& r, const TwoViewOptions& options) {
  return std::max(options.inlier_threshold, 4 * r.sigma);
}

namespace {

// The manifold dimension d and parameter count k GRIC gives `m`.
void GricFreedoms(MotionModel m, int* d, int* k) {
  *d = HasTranslation(m) ? 3 : 2;
  switch (m) {
    case MotionModel::kStatic: *k = 0; break;
    case MotionModel::kZoom: *k = 1; break;
    case MotionModel::kRotation: *k = 4; break;
    case MotionModel::kRotationZoom: *k = 5; break;
    default: *k = 5; break;
  }
}

// GRIC of `r`'s model over the matches `which` (residuals over every match).
double GricOn(const TwoViewResult& r, const std::vector<double>& sq, const std::vector<int>& which, double sigma) {
  std::vector<double> sub;
  sub.reserve(which.size());
  for (int i : which) sub.push_back(sq[i]);
  int d, k;
  GricFreedoms(r.model, &d, &k);
  return Gric(sub, sigma, d, k);
}

int Count(const std::vector<char>& mask, const std::vector<int>& which) {
  int c = 0;
  for (int i : which) c += mask[i] != 0;
  return c;
}

template <typename T>
std::vector<T> Pick(const std::vector<T>& v, const std::vector<int>& which) {
  std::vector<T> out;
  out.reserve(which.size());
  for (int i : which) out.push_back(v[i]);
  return out;
}

// `fit` (from a subset) as a result over every match: its inliers among all.
TwoViewResult OverAll(TwoViewResult fit, const std::vector<double>& sq, double threshold) {
  fit.inliers = TwoViewInliers(fit, sq, threshold);
  fit.num_points = static_cast<int>(sq.size());
  fit.num_inliers = static_cast<int>(std::count(fit.inliers.begin(), fit.inliers.end(), 1));
  return fit;
}

}  // namespace

namespace {

// Is the border's motion the camera's rather than the majority's? (See the
// header.) Two cases:
//  - the majority's motion nests the border's (a static border inside a
//    translating majority: a subject sliding over a still background is
//    exactly a camera sliding the other way with the background at
//    infinity). Only `static` is preferred then, and only if it explains
//    the border better by GRIC: a turning or zooming border around a
//    region with parallax is as often a rigid scene (a pan with a nodal
//    offset past a near object, the subject of a dolly zoom, which keeps
//    its size) as a subject moving on its own;
//  - otherwise the majority's motion must not hold the border (at most half
//    of its tracks): a large subject outnumbers the background, which
//    keeps the rest of the border.
bool BorderMotionWins(const TwoViewResult& all, const TwoViewResult& edge, const std::vector<double>& sq_all,
                      const std::vector<double>& sq_edge, const std::vector<char>& in_edge,
                      const std::vector<int>& border, double sigma) {
  // The border must hold one dominant motion to be evidence: where its best
  // motion does not explain the majority of it, it says nothing.
  if (2 * Count(in_edge, border) <= static_cast<int>(border.size())) return false;
  const bool nested = IsAtLeastAsGeneral(all.model, edge.model) && all.model != edge.model;
  if (nested)
    return edge.model == MotionModel::kStatic && GricOn(edge, sq_edge, border, sigma) < GricOn(all, sq_all, border, sigma);
  return 2 * Count(all.inliers, border) <= static_cast<int>(border.size());
}

}  // namespace

CameraMotion SelectCameraMotion(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                                double f1, double half_height, const TwoViewOptions& options,
                                const MoverOptions& movers) {
  CameraMotion out;
  const TwoViewResult all = SelectTwoViewModel(u1, u2, f1, options);
  out.camera = all;
  if (!movers.enabled || !all.valid) return out;
  const int n = static_cast<int>(u1.size());
  std::vector<int> border;
  for (int i = 0; i < n; ++i)
    if (BorderRadius(0.5 * (u1[i] + u2[i]), half_height) >= movers.border_radius) border.push_back(i);
  out.border_tracks = static_cast<int>(border.size());
  // A still majority that also holds the border: nothing else to try (the
  // common still shot costs no second fit).
  if (all.model == MotionModel::kStatic && 2 * Count(all.inliers, border) > out.border_tracks) return out;
  const TwoViewResult edge = SelectTwoViewModel(Pick(u1, border), Pick(u2, border), f1, options);
  if (!edge.valid) return out;
  const std::vector<double> sq_all = TwoViewResiduals(all, u1, u2);
  const std::vector<double> sq_edge = TwoViewResiduals(edge, u1, u2);
  const std::vector<char> in_edge = TwoViewInliers(edge, sq_edge, TwoViewThreshold(edge, options));
  int moving = 0;
  for (int i = 0; i < n; ++i) moving += all.inliers[i] && !in_edge[i];
  // One noise level for both (the majority's: measured on more tracks).
  const double sigma = std::max(all.sigma, options.noise_floor);
  if (moving < options.min_correspondences || !BorderMotionWins(all, edge, sq_all, sq_edge, in_edge, border, sigma))
    return out;
  // The border's motion is the camera's: refit it on every match it
  // explains (more tracks, a better pose), the rest are movers.
  std::vector<int> support;
  for (int i = 0; i < n; ++i)
    if (in_edge[i]) support.push_back(i);
  TwoViewResult cam = SelectTwoViewModel(Pick(u1, support), Pick(u2, support), f1, options);
  if (!cam.valid || cam.model != edge.model) cam = edge;
  out.camera = OverAll(cam, TwoViewResiduals(cam, u1, u2), TwoViewThreshold(cam, options));
  out.border_motion = true;
  out.mover.assign(n, 0);
  for (int i = 0; i < n; ++i) out.mover[i] = all.inliers[i] && !out.camera.inliers[i];
  out.movers = static_cast<int>(std::count(out.mover.begin(), out.mover.end(), 1));
  return out;
}

}  // namespace hapcine
