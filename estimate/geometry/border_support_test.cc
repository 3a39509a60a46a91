#include "estimate/geometry/border_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace hapcine {
namespace {

constexpr double kHalfHeight = 0.28125;  // 16:9

// `n` points spread uniformly over the part of the frame within Chebyshev
// radius `radius` (1: the whole frame) of the centre.
std::vector<Eigen::Vector2d> Within(double radius, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-0.5 * radius, 0.5 * radius),
      y(-kHalfHeight * radius, kHalfHeight * radius);
  std::vector<Eigen::Vector2d> u;
  for (int i = 0; i < n; ++i) u.emplace_back(x(rng), y(rng));
  return u;
}

TEST(BorderSupport, ATexturedFrameHoldsTheWholeEdge) {
  const std::vector<Eigen::Vector2d> u = Within(1, 150, 1);
  EXPECT_DOUBLE_EQ(BorderSupport(u, std::vector<char>(u.size(), 1), kHalfHeight), 1.0);
}

// A face over a dark background: the tracks within the central half of the
// frame (Chebyshev radius 0.5, the inner 2 x 2 cells) touch no edge cell;
// a subject filling one side leaves the other side's cells empty.
TEST(BorderSupport, ACompactRegionLeavesTheEdgeEmpty) {
  const std::vector<Eigen::Vector2d> inner = Within(0.49, 150, 2);
  EXPECT_DOUBLE_EQ(BorderSupport(inner, std::vector<char>(inner.size(), 1), kHalfHeight), 0.0);
  // A subject on the left half: the left two columns hold 6 of the 12 edge cells.
  std::vector<Eigen::Vector2d> left = Within(1, 150, 4);
  for (Eigen::Vector2d& p : left) p.x() = -std::abs(p.x());
  EXPECT_DOUBLE_EQ(BorderSupport(left, std::vector<char>(left.size(), 1), kHalfHeight), 6.0 / 12);
}

// Only the inliers count: a textured frame whose motion only a corner's
// tracks explain is held by one edge cell of twelve.
TEST(BorderSupport, OnlyInliersCount) {
  std::vector<Eigen::Vector2d> u = Within(1, 150, 5);
  std::vector<char> inlier(u.size(), 0);
  for (size_t i = 0; i < u.size(); ++i)
    inlier[i] = u[i].x() < -0.25 && u[i].y() < -0.5 * kHalfHeight;
  EXPECT_DOUBLE_EQ(BorderSupport(u, inlier, kHalfHeight), 1.0 / 12);
}

// Degenerate: no tracks, no inlier, every track in one cell, points off the
// frame or not finite (clamped to a cell, no out-of-range index).
TEST(BorderSupport, Degenerate) {
  EXPECT_DOUBLE_EQ(BorderSupport({}, {}, kHalfHeight), 0.0);
  const std::vector<Eigen::Vector2d> u = Within(1, 50, 6);
  EXPECT_DOUBLE_EQ(BorderSupport(u, std::vector<char>(u.size(), 0), kHalfHeight), 0.0);
  const std::vector<Eigen::Vector2d> one_cell(100, Eigen::Vector2d(0.45, 0.25));
  EXPECT_DOUBLE_EQ(BorderSupport(one_cell, std::vector<char>(100, 1), kHalfHeight), 1.0 / 12);
  const double inf = std::numeric_limits<double>::infinity(),
               nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector2d> odd = {{5, -5}, {1e300, -1e300}, {-inf, inf}, {nan, nan}};
  EXPECT_DOUBLE_EQ(BorderSupport(odd, {1, 1, 1, 1}, kHalfHeight),
                   1.0 / 12);  // the top right corner
  // A frame of no height places no point.
  EXPECT_DOUBLE_EQ(BorderSupport(u, std::vector<char>(u.size(), 1), 0.0), 0.0);
}

}  // namespace
}  // namespace hapcine
