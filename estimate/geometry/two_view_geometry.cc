#include "estimate/geometry/two_view_geometry.h"

#include <Eigen/Dense>
#include <cmath>

#include "estimate/geometry/two_view_estimators.h"

namespace hapcine {

bool DecomposeEssential(const Eigen::Matrix3d& E, const std::vector<Eigen::Vector2d>& c1,
                        const std::vector<Eigen::Vector2d>& c2, Eigen::Matrix3d* R_out,
                        Eigen::Vector3d* t_out) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU(), V = svd.matrixV();
  if (U.determinant() < 0) U = -U;
  if (V.determinant() < 0) V = -V;
  Eigen::Matrix3d W;
  W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const Eigen::Matrix3d Rs[2] = {U * W * V.transpose(), U * W.transpose() * V.transpose()};
  const Eigen::Vector3d u3 = U.col(2);
  int best = -1, best_count = 0;
  Eigen::Matrix3d best_R;
  Eigen::Vector3d best_t;
  for (const auto& R : Rs) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d t = sign * u3;
      int count = 0;
      for (size_t i = 0; i < c1.size(); ++i) {
        const double d1 = TriangulateDepth(c1[i], c2[i], R, t);
        if (!(d1 > 0)) continue;
        const Eigen::Vector3d X2 = R * (d1 * c1[i].homogeneous()) + t;
        if (X2.z() > 0) ++count;
      }
      if (count > best_count) {
        best_count = count;
        best_R = R;
        best_t = t;
        best = 1;
      }
    }
  }
  if (best < 0 || best_count * 2 < static_cast<int>(c1.size())) return false;
  *R_out = best_R;
  *t_out = best_t;
  return true;
}

bool FitRotation(const std::vector<Eigen::Vector2d>& c1, const std::vector<Eigen::Vector2d>& c2,
                 Eigen::Matrix3d* R) {
  const auto models = RotationEstimator::Estimate(c1, c2);
  if (models.empty()) return false;
  *R = models[0];
  return true;
}

namespace {

// Golden-section search of a function of log f on [lo, hi].
template <typename Fn>
double GoldenMin(Fn fn, double lo, double hi, int iterations, double* best_x) {
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, b = hi;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = fn(x1), f2 = fn(x2);
  for (int i = 0; i < iterations; ++i) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = fn(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = fn(x2);
    }
  }
  *best_x = f1 < f2 ? x1 : x2;
  return std::min(f1, f2);
}

double RotationCost(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                    double f1, double f2, Eigen::Matrix3d* R) {
  std::vector<Eigen::Vector2d> c1(u1.size()), c2(u2.size());
  for (size_t i = 0; i < u1.size(); ++i) {
    c1[i] = u1[i] / f1;
    c2[i] = u2[i] / f2;
  }
  if (!FitRotation(c1, c2, R)) return 1e30;
  double cost = 0;
  for (size_t i = 0; i < u1.size(); ++i) {
    const Eigen::Vector3d p = *R * c1[i].homogeneous();
    cost += p.z() > 1e-9 ? (f2 * p.hnormalized() - u2[i]).squaredNorm() : 1e6;
  }
  return cost;
}

}  // namespace

double FitRotationAndFocal(const std::vector<Eigen::Vector2d>& u1,
                           const std::vector<Eigen::Vector2d>& u2, double f0, double range,
                           double* f, Eigen::Matrix3d* R) {
  Eigen::Matrix3d Rt;
  auto fn = [&](double lf) { return RotationCost(u1, u2, std::exp(lf), std::exp(lf), &Rt); };
  double lf = std::log(f0);
  const double base = fn(lf);
  double best_lf;
  double cost = GoldenMin(fn, lf - std::log(range), lf + std::log(range), 40, &best_lf);
  // Prefer the given focal unless the data clearly say otherwise (flat cost
  // when the rotation is too small to observe f).
  if (!(cost < base * (1 - 1e-3))) {
    best_lf = lf;
    cost = base;
  }
  *f = std::exp(best_lf);
  RotationCost(u1, u2, *f, *f, R);
  return cost;
}

double FitRotationZoom(const std::vector<Eigen::Vector2d>& u1,
                       const std::vector<Eigen::Vector2d>& u2, double f1, double f2_0, double range,
                       double* f2, Eigen::Matrix3d* R) {
  Eigen::Matrix3d Rt;
  auto fn = [&](double lf) { return RotationCost(u1, u2, f1, std::exp(lf), &Rt); };
  double best_lf;
  const double cost =
      GoldenMin(fn, std::log(f2_0) - std::log(range), std::log(f2_0) + std::log(range), 40, &best_lf);
  *f2 = std::exp(best_lf);
  RotationCost(u1, u2, f1, *f2, R);
  return cost;
}

double TriangulateDepth(const Eigen::Vector2d& c1, const Eigen::Vector2d& c2,
                        const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  // In camera 1: ray a = d1 * r1 from 0; ray b = C2 + d2 * r2 with
  // C2 = -R^T t, r2 = R^T (c2, 1).
  const Eigen::Vector3d r1 = c1.homogeneous();
  const Eigen::Vector3d r2 = R.transpose() * c2.homogeneous();
  const Eigen::Vector3d C2 = -R.transpose() * t;
  // Solve [r1 -r2] [d1 d2]^T ~= C2 in least squares.
  const double a = r1.dot(r1), b = r1.dot(r2), c = r2.dot(r2);
  const double d = r1.dot(C2), e = r2.dot(C2);
  const double den = a * c - b * b;
  if (!(den > 1e-12 * a * c)) return 0;  // parallel rays: at infinity
  const double d1 = (c * d - b * e) / den;
  return std::isfinite(d1) ? d1 : 0;
}

}  // namespace hapcine
