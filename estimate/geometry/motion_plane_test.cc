#include "estimate/geometry/motion_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace hapcine {
namespace {

// (x, y, w) of a floor 1.5 below a level camera (OpenCV axes, y down) from 5
// to 25 ahead, a subject 7 ahead and a back wall 25 ahead; `noise` on w.
std::vector<Eigen::Vector3d> FloorSubjectWall(int floor_points, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> n(0, noise);
  std::vector<Eigen::Vector3d> xyw;
  for (int i = 0; i < floor_points; ++i) {
    const double z = 5 + 10 * (u(rng) + 1);
    xyw.emplace_back(0.3 * u(rng), 1.5 / z, 1 / z + n(rng));
  }
  for (int i = 0; i < 100; ++i) xyw.emplace_back(0.05 * u(rng), 0.08 * u(rng), 1 / 7.0 + n(rng));
  for (int i = 0; i < 150; ++i) xyw.emplace_back(0.3 * u(rng), -0.1 + 0.1 * u(rng), 1 / 25.0 + n(rng));
  return xyw;
}

TEST(MotionPlane, FindsTheFloorBesideASubjectAndAWall) {
  for (double noise : {0.0, 0.0005, 0.001}) {
    const auto plane = FindSlopedPlane(FloorSubjectWall(80, noise, 1));
    ASSERT_TRUE(plane) << noise;
    // The floor: w = y / 1.5, through the principal point's row at w = 0.
    EXPECT_NEAR(plane->n.x(), 0, 0.02) << noise;
    EXPECT_NEAR(plane->n.y(), 1 / 1.5, 0.02) << noise;
    EXPECT_NEAR(plane->n.z(), 0, 0.002) << noise;
    EXPECT_GE(plane->inliers, 70) << noise;
  }
}

TEST(MotionPlane, TheSameInputGivesTheSamePlane) {
  const auto xyw = FloorSubjectWall(80, 0.001, 2);
  const auto a = FindSlopedPlane(xyw), b = FindSlopedPlane(xyw);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->n, b->n);
}

TEST(MotionPlane, PlanesFacingTheCameraAreNotSloped) {
  // Only the subject and the wall: each is a plane, neither is a floor.
  EXPECT_FALSE(FindSlopedPlane(FloorSubjectWall(0, 0.0005, 3)));
}

TEST(MotionPlane, TooFewFloorPointsAreNoPlane) {
  EXPECT_FALSE(FindSlopedPlane(FloorSubjectWall(8, 0.0, 4)));
}

TEST(MotionPlane, ARandomCloudHasNoPlane) {
  // Foliage, clutter: points at every depth everywhere.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> xyw;
  for (int i = 0; i < 1500; ++i) xyw.emplace_back(0.4 * u(rng), 0.25 * u(rng), 0.1 + 0.05 * (u(rng) + 1));
  EXPECT_FALSE(FindSlopedPlane(xyw));
}

TEST(MotionPlane, TwoClustersAreNoPlane) {
  // A plane through the wall and the subject touches a few points of each,
  // with nothing in between.
  std::vector<Eigen::Vector3d> xyw;
  for (int i = 0; i < 20; ++i) {
    xyw.emplace_back(0.01 * i, 0.0, 0.04);   // a row of the wall
    xyw.emplace_back(0.01 * i, 0.1, 0.143);  // a row of the subject
  }
  EXPECT_FALSE(FindSlopedPlane(xyw));
}

TEST(MotionPlane, DegenerateInputIsNoPlaneAndNoCrash) {
  EXPECT_FALSE(FindSlopedPlane({}));
  EXPECT_FALSE(FindSlopedPlane({{0, 0, 1}, {1, 0, 1}}));
  // Collinear in the image: every sample is rank-deficient.
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 100; ++i) line.emplace_back(0.0, 0.001 * i, 0.01 * i);
  EXPECT_FALSE(FindSlopedPlane(line));
  // Non-finite points are skipped, not fitted.
  auto xyw = FloorSubjectWall(80, 0.0, 6);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  xyw.emplace_back(nan, 0.1, 0.1);
  xyw.emplace_back(0.1, 0.1, std::numeric_limits<double>::infinity());
  const auto plane = FindSlopedPlane(xyw);
  ASSERT_TRUE(plane);
  EXPECT_TRUE(plane->n.allFinite());
  EXPECT_NEAR(plane->n.y(), 1 / 1.5, 1e-6);
}

}  // namespace
}  // namespace hapcine
