#include "estimate/window/focal_profile.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace hapcine {

double SumOfFiniteSquares(const std::vector<double>& e) {
  double s = 0;
  for (double v : e) s += std::isfinite(v) ? v * v : 0.0;
  return s;
}

std::vector<double> DefaultFocalProfileShifts() { return {-0.04, -0.02, -0.01, 0.0, 0.01, 0.02, 0.03, 0.04}; }

bool FitParabola(const std::vector<double>& x, const std::vector<double>& y, double* a, double* b, double* c) {
  std::vector<int> use;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) use.push_back(static_cast<int>(i));
  if (use.size() < 3) return false;
  Eigen::MatrixXd m(use.size(), 3);
  Eigen::VectorXd v(use.size());
  for (size_t r = 0; r < use.size(); ++r) {
    const double t = x[use[r]];
    m.row(r) << t * t, t, 1.0;
    v(r) = y[use[r]];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  if (qr.rank() < 3) return false;
  const Eigen::Vector3d p = qr.solve(v);
  *a = p(0);
  *b = p(1);
  *c = p(2);
  return true;
}

namespace {

// Residuals in units of each observation's own noise (noise_scale), as the
// solve weighs them.
std::vector<double> WeightedErrors(const std::vector<BaCamera>& cameras, const std::vector<BaPoint>& points,
                                   const std::vector<BaObservation>& observations, bool use_depth) {
  std::vector<double> e = ObservationErrors(cameras, points, observations, use_depth);
  for (size_t i = 0; i < e.size(); ++i) e[i] /= observations[i].noise_scale;
  return e;
}

}  // namespace

FocalProfile ProfileFocal(const BaOptions& ba, const std::vector<BaCamera>& cameras,
                          const std::vector<BaPoint>& points, const std::vector<BaObservation>& observations,
                          const std::vector<double>& log_shifts) {
  FocalProfile prof;
  prof.log_shifts = log_shifts;
  // One sigma for every shift: the residual variance of the window as solved.
  const double m = static_cast<double>(observations.size());
  const double var0 = m > 0 ? SumOfFiniteSquares(WeightedErrors(cameras, points, observations, ba.use_depth)) / m : 0;
  for (double shift : log_shifts) {
    std::vector<BaCamera> cams = cameras;
    std::vector<BaPoint> pts = points;
    for (auto& c : cams) {
      c.log_focal += shift;
      c.fixed_focal = true;
    }
    const BaSummary s = SolveBundle(&cams, &pts, observations, ba);
    prof.errors.push_back(WeightedErrors(cams, pts, observations, ba.use_depth));
    const double ss = SumOfFiniteSquares(prof.errors.back());
    prof.chi2.push_back(s.success && var0 > 0 ? ss / var0 : std::numeric_limits<double>::quiet_NaN());
  }
  // The parabola on the inner shifts only: farther out the solve can fall
  // into another minimum (the wider shifts show whether there is one).
  std::vector<double> inner_shifts, inner_chi2;
  for (size_t i = 0; i < log_shifts.size(); ++i)
    if (std::abs(log_shifts[i]) <= kFocalProfileFitHalfWidth + 1e-12) {
      inner_shifts.push_back(log_shifts[i]);
      inner_chi2.push_back(prof.chi2[i]);
    }
  double a = 0, b = 0, c = 0;
  prof.sigma_log_focal = std::numeric_limits<double>::infinity();
  if (FitParabola(inner_shifts, inner_chi2, &a, &b, &c) && a > 0) {
    prof.curvature = a;
    prof.sigma_log_focal = 1.0 / std::sqrt(a);
    prof.minimum_log_shift = -b / (2 * a);
  } else {
    prof.curvature = a;
  }
  return prof;
}

}  // namespace hapcine
