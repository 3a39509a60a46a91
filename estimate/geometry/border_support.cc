#include "estimate/geometry/border_support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/statistics.h"
#include "estimate/geometry/motion_hypotheses.h"

namespace hapcine {
namespace {

// The grid column or row of coordinate `x` in [-half, half] (beyond: the
// nearest); -1 when it has none (not finite, or a frame of no extent).
int Cell(double x, double half) {
  const double t = (x + half) / (2 * half) * kBorderGridCells;
  if (!std::isfinite(t)) return -1;
  return static_cast<int>(std::clamp(std::floor(t), 0.0, kBorderGridCells - 1.0));
}

}  // namespace

double BorderSupport(const std::vector<Eigen::Vector2d>& u, const std::vector<char>& inlier,
                     double half_height) {
  constexpr int n = kBorderGridCells;
  std::vector<char> held(n * n, 0);
  for (size_t i = 0; i < u.size() && i < inlier.size(); ++i) {
    if (!inlier[i]) continue;
    const int row = Cell(u[i].y(), half_height), col = Cell(u[i].x(), 0.5);
    if (row >= 0 && col >= 0) held[row * n + col] = 1;
  }
  int edge = 0, edge_held = 0;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      if (row != 0 && col != 0 && row != n - 1 && col != n - 1) continue;
      ++edge;
      edge_held += held[row * n + col];
    }
  return static_cast<double>(edge_held) / edge;
}

StillBorder StillBorderTracks(const TwoViewResult& motion, const std::vector<Eigen::Vector2d>& u1,
                              const std::vector<Eigen::Vector2d>& u2, double threshold,
                              double half_height, double border_radius) {
  StillBorder out;
  for (size_t i = 0; i < u1.size() && i < u2.size(); ++i) {
    if (BorderRadius(0.5 * (u1[i] + u2[i]), half_height) < border_radius) continue;
    const Eigen::Vector2d x = u1[i] / motion.f1;
    const Eigen::Vector3d ray = motion.cam2_from_cam1 * x.homogeneous();
    if (!(ray.z() > 0) || !((motion.f2 * ray.hnormalized() - u1[i]).norm() >= 2 * threshold))
      continue;
    ++out.moved_by_turn;
    out.still += (u2[i] - u1[i]).norm() <= threshold;
  }
  return out;
}

bool StillBorderAroundMotion(const std::vector<double>& support,
                             const std::vector<StillBorder>& border) {
  if (support.empty() || support.size() != border.size()) return false;
  int tested = 0, held = 0;
  long still = 0, moved = 0;
  for (const StillBorder& b : border) {
    if (b.moved_by_turn < kMinStillBorderTracks) continue;  // nothing the turn would move
    ++tested;
    held += b.still >= kMinStillBorderTracks;
    still += b.still;
    moved += b.moved_by_turn;
  }
  if (tested == 0 || 2 * held <= tested) return false;
  const bool unconfirmed = Median(support) < kUnconfirmedBorderSupport;
  return unconfirmed || 2 * still > moved;
}

}  // namespace hapcine
