#include "estimate/geometry/motion_plane.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/statistics.h"

namespace hapcine {
namespace {

// w range (2nd..98th percentile) of the points `idx` of `xyw`.
double WRange(const std::vector<Eigen::Vector3d>& xyw, const std::vector<int>& idx) {
  std::vector<double> w;
  w.reserve(idx.size());
  for (int i : idx) w.push_back(xyw[i].z());
  return Quantile(w, 0.98) - Quantile(w, 0.02);
}

// Least-squares plane w = n . (x, y, 1) through the points `idx`.
std::optional<Eigen::Vector3d> FitPlane(const std::vector<Eigen::Vector3d>& xyw, const std::vector<int>& idx) {
  Eigen::MatrixXd a(idx.size(), 3);
  Eigen::VectorXd b(idx.size());
  for (size_t r = 0; r < idx.size(); ++r) {
    const Eigen::Vector3d& p = xyw[idx[r]];
    a.row(r) << p.x(), p.y(), 1;
    b(r) = p.z();
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 3) return std::nullopt;  // collinear in the image
  const Eigen::Vector3d n = qr.solve(b);
  if (!n.allFinite()) return std::nullopt;
  return n;
}

std::vector<int> Inliers(const std::vector<Eigen::Vector3d>& xyw, const Eigen::Vector3d& n, double tol) {
  std::vector<int> in;
  for (size_t i = 0; i < xyw.size(); ++i)
    if (std::abs(n.dot(Eigen::Vector3d(xyw[i].x(), xyw[i].y(), 1)) - xyw[i].z()) <= tol)
      in.push_back(static_cast<int>(i));
  return in;
}

}  // namespace

std::optional<InverseDepthPlane> FindSlopedPlane(const std::vector<Eigen::Vector3d>& points,
                                                 const PlaneSearchOptions& options,
                                                 const std::function<bool(const Eigen::Vector3d& n)>& admit) {
  std::vector<Eigen::Vector3d> xyw;
  xyw.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) xyw.push_back(p);
  const int m = static_cast<int>(xyw.size());
  const int need = std::max(options.min_inliers, static_cast<int>(std::ceil(options.min_support * m)));
  if (m < std::max(need, 3)) return std::nullopt;
  std::vector<int> all(m);
  for (int i = 0; i < m; ++i) all[i] = i;
  const double range = WRange(xyw, all);
  if (!(range > 0) || !std::isfinite(range)) return std::nullopt;
  const double tol = options.tolerance_share * range;

  // Only sloped planes compete: otherwise the wall facing the camera (often
  // the most points) would win every time.
  auto sloped = [&](const std::vector<int>& in) {
    if (static_cast<int>(in.size()) < need) return false;
    std::vector<double> w;
    for (int i : in) w.push_back(xyw[i].z());
    std::sort(w.begin(), w.end());
    const double span = w.back() - w.front();
    auto sorted_quantile = [&](double q) { return w[std::min(w.size() - 1, static_cast<size_t>(q * w.size()))]; };
    if (sorted_quantile(0.98) - sorted_quantile(0.02) < options.min_slope_share * range) return false;
    for (size_t i = 1; i < w.size(); ++i)
      if (w[i] - w[i - 1] > options.max_gap_share * span) return false;
    return true;
  };
  std::mt19937 rng(options.seed);
  std::uniform_int_distribution<int> pick(0, m - 1);
  std::optional<InverseDepthPlane> best;
  for (int it = 0; it < options.iterations; ++it) {
    const int i = pick(rng), j = pick(rng), k = pick(rng);
    if (i == j || j == k || i == k) continue;
    const auto n = FitPlane(xyw, {i, j, k});
    if (!n) continue;
    const std::vector<int> in = Inliers(xyw, *n, tol);
    if ((best && static_cast<int>(in.size()) <= best->inliers) || !sloped(in)) continue;
    // Refit on the inliers, then take the refit's inliers once more.
    const auto refit = FitPlane(xyw, in);
    if (!refit) continue;
    const std::vector<int> in2 = Inliers(xyw, *refit, tol);
    if (!sloped(in2) || (best && static_cast<int>(in2.size()) <= best->inliers)) continue;
    const auto final_n = FitPlane(xyw, in2);
    if (!final_n || (admit && !admit(*final_n))) continue;
    best = InverseDepthPlane{*final_n, static_cast<int>(in2.size())};
  }
  return best;
}

}  // namespace hapcine
