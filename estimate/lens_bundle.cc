#include "estimate/lens_bundle.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>
#include <ceres/sphere_manifold.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/statistics.h"
#include "estimate/geometry/reference_width.h"
#include "estimate/lens_distortion.h"

namespace hapcine {
namespace {

// |k1| > 2 sigma: the chi2 gain must exceed 2^2.
constexpr double kMinSigmas = 2;
// Capped chi2: an observation counts at most (4 sigma)^2, as an outlier would.
constexpr double kChi2Cap = 16;
constexpr int kIterations = 100;
constexpr int kDistortIterations = 8;
// Windows that must pay for their own k1 before the pooled one is kept: a
// lens confirmed by at least one other window.
constexpr int kMinPayingWindows = 2;

// Residual of one observation: the point projected by the camera (focal
// constant) and distorted by k1, minus the observation, in units of
// `scale`. In the observation's space: undistorting the observations
// instead would scale their noise by the lens, and a barrel-to-pincushion
// k1 that shrinks the noise at the corners would pay for itself on pinhole
// footage. `point` is (X, w) homogeneous with depth, or a bearing (no depth).
struct LensCost {
  LensCost(const Eigen::Vector2d& u, double focal, double r2_per_u2, double inv_scale, bool depth)
      : u_(u), focal_(focal), r2_per_u2_(r2_per_u2), inv_scale_(inv_scale), depth_(depth) {}
  template <typename T>
  bool operator()(const T* q, const T* c, const T* point, const T* lens, T* r) const {
    Eigen::Map<const Eigen::Quaternion<T>> world_from_cam(q);
    Eigen::Matrix<T, 3, 1> v(point[0], point[1], point[2]);
    if (depth_) v -= point[3] * Eigen::Matrix<T, 3, 1>(c[0], c[1], c[2]);
    const Eigen::Matrix<T, 3, 1> p = world_from_cam.conjugate() * v;
    if (!(p.z() > T(1e-9) * ceres::sqrt(p.squaredNorm() + T(1e-300)))) return false;
    const T focal = T(focal_) * ceres::exp(lens[1]);
    const T x = focal * p.x() / p.z(), y = focal * p.y() / p.z();
    // The distorted position d with d (1 + k1 r(d)^2) = (x, y): fixed point,
    // a contraction for |k1| r^2 < 1/2 (the range, inside the picture).
    T dx = x, dy = y;
    for (int i = 0; i < kDistortIterations; ++i) {
      const T scale = T(1) + lens[0] * T(r2_per_u2_) * (dx * dx + dy * dy);
      dx = x / scale;
      dy = y / scale;
    }
    r[0] = (dx - T(u_.x())) * T(inv_scale_);
    r[1] = (dy - T(u_.y())) * T(inv_scale_);
    return true;
  }
  Eigen::Vector2d u_;
  double focal_, r2_per_u2_, inv_scale_;
  bool depth_;
};

// The window's parameters, one block per camera (no sharing: the extra
// freedoms cost no bias in k1) and per point.
struct LensProblem {
  std::vector<std::array<double, 4>> q;
  std::vector<std::array<double, 3>> c;
  std::vector<std::array<double, 4>> x;  // (X, w) or (bearing, 0)
  // k1, and the log of one factor on every camera's focal: k1 must pay
  // for itself beyond what a focal change explains (a focal held at a
  // wrong prior bends a rotation's tracks radially too). The factor found
  // is not used: the window decided the focal.
  std::array<double, 2> lens{0, 0};
};

// The first camera's centre is moved to the origin (the other centres and
// the points with it), so that the farthest centre's distance from it can
// be held by a sphere: the scale's gauge.
LensProblem Parameters(const SolvedWindow& w) {
  LensProblem p;
  const Eigen::Vector3d origin = w.cameras.front().center;
  for (const BaCamera& cam : w.cameras) {
    const Eigen::Quaterniond q = cam.world_from_cam.normalized();
    const Eigen::Vector3d c = cam.center - origin;
    p.q.push_back({q.x(), q.y(), q.z(), q.w()});
    p.c.push_back({c.x(), c.y(), c.z()});
  }
  for (const BaPoint& pt : w.points) {
    const double rho = w.use_depth ? pt.homogeneous(3) : 0;
    Eigen::Vector4d h;
    h << pt.Direction() + rho * (pt.anchor - origin), rho;
    if (!w.use_depth) h.head<3>().normalize();
    else h.normalize();
    p.x.push_back({h(0), h(1), h(2), h(3)});
  }
  return p;
}

// The camera whose centre is farthest from the first's (the origin), or -1.
int ScaleCamera(const SolvedWindow& w, const LensProblem& p) {
  int farthest = -1;
  double far = 1e-9;
  for (size_t i = 1; i < w.cameras.size(); ++i) {
    const double d = Eigen::Vector3d(p.c[i][0], p.c[i][1], p.c[i][2]).norm();
    if (d > far) far = d, farthest = static_cast<int>(i);
  }
  return farthest;
}

double R2PerU2(int width, int height) {
  const double half_diagonal = 0.5 * std::hypot(width, height);
  return (width / half_diagonal) * (width / half_diagonal);
}

// Solves `p` from where it stands, k1 free (within the range) or held.
bool Solve(const SolvedWindow& w, int width, int height, bool free_k1, double max_abs_k1, LensProblem* p) {
  ceres::Problem problem;
  const double inv_scale = kReferenceWidthPx;  // ~1 px residual units
  const double r2 = R2PerU2(width, height);
  for (const BaObservation& o : w.observations) {
    auto* cost = new ceres::AutoDiffCostFunction<LensCost, 2, 4, 3, 4, 2>(new LensCost(
        o.u, std::exp(w.cameras[o.camera].log_focal), r2, inv_scale, w.use_depth));
    problem.AddResidualBlock(cost, new ceres::HuberLoss(1.0), p->q[o.camera].data(), p->c[o.camera].data(),
                             p->x[o.point].data(), p->lens.data());
  }
  // The first camera is the gauge, and the scale: the farthest centre stays
  // as far. The window's other held cameras (its overlap with the previous
  // window) are free: solved at k1 = 0 they carry that window's lens error,
  // and each window must measure k1 on its own (EstimateK1InWindows).
  const int scale_camera = w.use_depth ? ScaleCamera(w, *p) : -1;
  for (size_t i = 0; i < w.cameras.size(); ++i) {
    if (!problem.HasParameterBlock(p->q[i].data())) continue;
    problem.SetManifold(p->q[i].data(), new ceres::EigenQuaternionManifold);
    if (i == 0) {
      problem.SetParameterBlockConstant(p->q[i].data());
      problem.SetParameterBlockConstant(p->c[i].data());
    } else if (!w.use_depth) {
      problem.SetParameterBlockConstant(p->c[i].data());  // bearings: the centres mean nothing
    } else if (static_cast<int>(i) == scale_camera) {
      problem.SetManifold(p->c[i].data(), new ceres::SphereManifold<3>);
    }
  }
  // Bearings ignore the 4th coordinate: one more null direction, as the scale.
  for (auto& x : p->x)
    if (problem.HasParameterBlock(x.data())) problem.SetManifold(x.data(), new ceres::SphereManifold<4>);
  if (!problem.HasParameterBlock(p->lens.data())) return false;
  if (free_k1) {
    problem.SetParameterLowerBound(p->lens.data(), 0, -max_abs_k1);
    problem.SetParameterUpperBound(p->lens.data(), 0, max_abs_k1);
  } else {
    problem.SetManifold(p->lens.data(), new ceres::SubsetManifold(2, {0}));  // k1 held, the focal free
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = kIterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;  // algorithms print nothing (a step behind a camera warned)
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.IsSolutionUsable();
}

// Each observation's residual (2 components, normalised units); behind the
// camera: none.
std::vector<Eigen::Vector2d> Residuals(const SolvedWindow& w, int width, int height, const LensProblem& p) {
  std::vector<Eigen::Vector2d> out;
  const double r2 = R2PerU2(width, height);
  for (const BaObservation& o : w.observations) {
    const LensCost cost(o.u, std::exp(w.cameras[o.camera].log_focal), r2, 1.0, w.use_depth);
    Eigen::Vector2d r;
    if (cost(p.q[o.camera].data(), p.c[o.camera].data(), p.x[o.point].data(), p.lens.data(), r.data()))
      out.push_back(r);
  }
  return out;
}

// Robust sigma of the residuals' components (MAD), at least the floor.
double NoiseSigma(const std::vector<Eigen::Vector2d>& r, double floor) {
  std::vector<double> a;
  for (const auto& e : r) a.push_back(std::abs(e.x())), a.push_back(std::abs(e.y()));
  return a.empty() ? floor : std::max(floor, 1.4826 * Median(a));
}

int PointsObserved(const SolvedWindow& w) {
  std::vector<bool> seen(w.points.size(), false);
  int n = 0;
  for (const BaObservation& o : w.observations)
    if (o.point >= 0 && o.point < static_cast<int>(seen.size()) && !seen[o.point]) seen[o.point] = true, ++n;
  return n;
}

double CappedChi2(const std::vector<Eigen::Vector2d>& r, double sigma) {
  double chi2 = 0;
  for (const auto& e : r) chi2 += std::min(e.squaredNorm() / (sigma * sigma), kChi2Cap);
  return chi2;
}

}  // namespace

LensBundleEstimate EstimateK1InWindow(const SolvedWindow& window, int width, int height, double max_abs_k1) {
  LensBundleEstimate out;
  out.observations = static_cast<int>(window.observations.size());
  if (window.cameras.size() < 3 || window.points.empty() || out.observations < 20 || width <= 0 || height <= 0)
    return out;
  LensProblem held = Parameters(window);
  if (!Solve(window, width, height, false, max_abs_k1, &held)) return out;
  LensProblem free = held;
  if (!Solve(window, width, height, true, max_abs_k1, &free)) return out;
  // k1 = 0 again from where the free solve ended: along a flat valley (a
  // traveling's rotation against its depths) the first held solve can stop
  // short, and the free one's gain would be the valley's, not the lens's.
  LensProblem again = free;
  again.lens[0] = 0;
  if (Solve(window, width, height, false, max_abs_k1, &again) &&
      CappedChi2(Residuals(window, width, height, again), 1) < CappedChi2(Residuals(window, width, height, held), 1))
    held = again;
  out.solved = true;
  out.best_k1 = free.lens[0];
  const std::vector<Eigen::Vector2d> at_k1 = Residuals(window, width, height, free);
  const std::vector<Eigen::Vector2d> at_zero = Residuals(window, width, height, held);
  // The noise of the model with k1 (the larger one); capped chi2 at both.
  const double sigma = NoiseSigma(at_k1, kLensNoiseFloorPx / kReferenceWidthPx);
  out.noise_px = sigma * width;
  out.chi2_gain = CappedChi2(at_zero, sigma) - CappedChi2(at_k1, sigma);
  out.penalty = std::max(std::log(2.0 * at_k1.size()), kMinSigmas * kMinSigmas);
  out.sigma_k1 = out.chi2_gain > 0 ? std::abs(free.lens[0]) / std::sqrt(out.chi2_gain) : 0;
  out.points = PointsObserved(window);
  if (out.points > 0) out.track_sigma_k1 = out.sigma_k1 * std::sqrt(double(out.observations) / out.points);
  // At the end of the range: no lens, a model the data break.
  const bool inside = std::abs(free.lens[0]) < 0.96 * max_abs_k1;
  if (out.chi2_gain > out.penalty && std::abs(free.lens[0]) >= kMinLensK1 && inside) out.k1 = free.lens[0];
  return out;
}

namespace {

// chi2's 95 % quantile with `dof` degrees of freedom (1..5; above, the
// Wilson-Hilferty approximation).
double Chi2Quantile95(int dof) {
  static const double kTable[] = {3.841, 5.991, 7.815, 9.488, 11.070};
  if (dof >= 1 && dof <= 5) return kTable[dof - 1];
  const double a = 2.0 / (9.0 * dof);
  return dof * std::pow(1 - a + 1.645 * std::sqrt(a), 3);
}

}  // namespace

LensAgreement EstimateK1InWindows(const std::vector<SolvedWindow>& windows, int width, int height,
                                  double max_abs_k1) {
  LensAgreement out;
  double weight_sum = 0, weighted_k1 = 0;
  bool inside = true;
  for (size_t i = 0; i < windows.size(); ++i) {
    // Two windows must pay for their own k1: once too few are left for
    // that, the rest cannot change the decision and are not measured.
    if (out.significant + static_cast<int>(windows.size() - i) < kMinPayingWindows) break;
    out.windows.push_back(EstimateK1InWindow(windows[i], width, height, max_abs_k1));
    const LensBundleEstimate& e = out.windows.back();
    // A window whose k1 has no profile (no gain) measures nothing.
    if (!e.solved || e.track_sigma_k1 <= 0) continue;
    inside = inside && std::abs(e.best_k1) < 0.96 * max_abs_k1;
    ++out.measuring;
    // Its own test's gain (the 0.005 floor is the pooled k1's).
    out.significant += e.chi2_gain > e.penalty;
    const double weight = 1 / (e.track_sigma_k1 * e.track_sigma_k1);
    weight_sum += weight;
    weighted_k1 += weight * e.best_k1;
  }
  if (out.measuring < 2) return out;
  out.pooled_k1 = weighted_k1 / weight_sum;
  out.sigma = 1 / std::sqrt(weight_sum);
  out.same_sign = true;
  for (const LensBundleEstimate& e : out.windows) {
    if (!e.solved || e.track_sigma_k1 <= 0) continue;
    out.spread_chi2 += std::pow((e.best_k1 - out.pooled_k1) / e.track_sigma_k1, 2);
    out.same_sign = out.same_sign && e.best_k1 * out.pooled_k1 > 0;
  }
  out.spread_limit = Chi2Quantile95(out.measuring - 1);
  if (out.significant >= kMinPayingWindows && out.same_sign && out.spread_chi2 <= out.spread_limit && inside &&
      std::abs(out.pooled_k1) >= kMinLensK1)
    out.k1 = out.pooled_k1;
  return out;
}

}  // namespace hapcine
