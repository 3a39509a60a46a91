#include "estimate/geometry/border_support.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>

#include "estimate/geometry/motion_hypotheses.h"

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

// A pan of 2 degrees at a focal of 1 (normalised): every point of a rigid
// scene moves by about 0.035 of the width.
TwoViewResult Pan(double deg) {
  TwoViewResult r;
  r.valid = true;
  r.model = MotionModel::kRotation;
  r.cam2_from_cam1 =
      Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return r;
}

std::vector<Eigen::Vector2d> Moved(const TwoViewResult& r, const std::vector<Eigen::Vector2d>& u) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : u)
    out.push_back((r.cam2_from_cam1 * p.homogeneous()).hnormalized());
  return out;
}

constexpr double kThreshold = 1.5 / 960;
constexpr double kRadius = 0.8;

// Border tracks that stay where the pan would move them are counted; those
// inside the band are not (a subject), nor those that moved with the pan.
TEST(StillBorderTracks, CountsTheBorderTracksAPanWouldMoveThatStayed) {
  const TwoViewResult pan = Pan(2);
  const std::vector<Eigen::Vector2d> u1 = Within(1, 300, 7);
  int border = 0;
  for (const Eigen::Vector2d& p : u1) border += BorderRadius(p, kHalfHeight) >= kRadius;
  const StillBorder moving =
      StillBorderTracks(pan, u1, Moved(pan, u1), kThreshold, kHalfHeight, kRadius);
  EXPECT_GT(moving.moved_by_turn, border * 9 / 10);  // the midpoint may fall just inside the band
  EXPECT_EQ(moving.still, 0);
  const StillBorder still = StillBorderTracks(pan, u1, u1, kThreshold, kHalfHeight, kRadius);
  EXPECT_EQ(still.still, still.moved_by_turn);
  EXPECT_EQ(still.moved_by_turn, border);
}

// A translation alone, or a turn under the noise, tests nothing: far points
// stay still under a traveling, and a still point is no contradiction.
TEST(StillBorderTracks, ATranslationOrATinyTurnTestsNothing) {
  const std::vector<Eigen::Vector2d> u1 = Within(1, 300, 8);
  TwoViewResult travel;
  travel.valid = true;
  travel.model = MotionModel::kGeneral;
  travel.translation = Eigen::Vector3d(1, 0, 0);
  EXPECT_EQ(StillBorderTracks(travel, u1, u1, kThreshold, kHalfHeight, kRadius).moved_by_turn, 0);
  EXPECT_EQ(StillBorderTracks(Pan(0.1), u1, u1, kThreshold, kHalfHeight, kRadius).moved_by_turn, 0);
}

// Degenerate: no tracks, mismatched lists, points behind the camera after
// the turn, non-finite points.
TEST(StillBorderTracks, Degenerate) {
  const TwoViewResult pan = Pan(2);
  EXPECT_EQ(StillBorderTracks(pan, {}, {}, kThreshold, kHalfHeight, kRadius).moved_by_turn, 0);
  const std::vector<Eigen::Vector2d> u1 = Within(1, 20, 9);
  EXPECT_EQ(StillBorderTracks(pan, u1, {}, kThreshold, kHalfHeight, kRadius).moved_by_turn, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector2d> odd = {{nan, nan}, {1e9, 0}};
  const StillBorder s = StillBorderTracks(Pan(120), odd, odd, kThreshold, kHalfHeight, kRadius);
  EXPECT_EQ(s.still, 0);
}

// The shot rule: the border still in most of the intervals that test it,
// and the motion unconfirmed (median support below one half) or most of the
// border it would move still.
TEST(StillBorderAroundMotion, AStillBorderAroundAnUnconfirmedMotionIsAStillCamera) {
  const StillBorder none{0, 0};  // a still interval, or a turn under the noise
  // A talking face over a dark room with a candle at the edge: the motion
  // holds a third of the edge cells, the candle stays.
  EXPECT_TRUE(StillBorderAroundMotion({0.33, 0.42, 0.25, 0.33}, {{12, 3}, {16, 8}, none, {32, 0}}));
  // A subject that reaches the edge (support 0.92) while most of the
  // border its turn would move stays still.
  EXPECT_TRUE(StillBorderAroundMotion({0.92, 0.92, 1.0}, {{34, 24}, none, none}));
}

TEST(StillBorderAroundMotion, AMovingBorderOrTooLittleStillnessKeepsTheMotion) {
  const StillBorder none{0, 0};
  // A pan with a logo: the logo's tracks stay in every interval, but the
  // motion holds the edge and most of the border moves with it.
  EXPECT_FALSE(StillBorderAroundMotion({1.0, 0.92, 1.0}, {{150, 12}, {140, 12}, {160, 11}}));
  // Unconfirmed, but still in exactly half the tested intervals: not most.
  EXPECT_FALSE(StillBorderAroundMotion({0.33, 0.42, 0.25, 0.33}, {{12, 3}, {16, 0}, none, none}));
  // Too few still tracks: a stray stuck track or two.
  EXPECT_FALSE(StillBorderAroundMotion({0.33, 0.42, 0.25}, {{10, 2}, {10, 2}, {10, 1}}));
  // An object turned over an empty background: nothing at the border to test.
  EXPECT_FALSE(StillBorderAroundMotion({0.33, 0.42, 0.25}, {none, {2, 2}, none}));
  // Confirmed (median support exactly one half is not below it) and most of
  // the border moving.
  EXPECT_FALSE(StillBorderAroundMotion({0.5, 0.5, 0.5}, {{20, 5}, {20, 5}, {20, 5}}));
}

TEST(StillBorderAroundMotion, Degenerate) {
  EXPECT_FALSE(StillBorderAroundMotion({}, {}));
  EXPECT_FALSE(StillBorderAroundMotion({0.2, 0.2}, {{5, 5}}));  // lists of different lengths
  // No finite support (no median): the share alone decides.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(StillBorderAroundMotion({nan, nan}, {{20, 5}, {20, 5}}));
  EXPECT_TRUE(StillBorderAroundMotion({nan, nan}, {{20, 15}, {20, 15}}));
}

}  // namespace
}  // namespace hapcine
