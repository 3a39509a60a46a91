#include "estimate/geometry/border_support.h"

#include <algorithm>
#include <cmath>

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

}  // namespace hapcine
