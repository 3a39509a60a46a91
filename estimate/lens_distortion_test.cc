#include "estimate/lens_distortion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimate/test_scene.h"

namespace hapcine {
namespace {

using testing::MakeFrameTracks;
using testing::RandomPoints;
using testing::SceneCamera;

constexpr int kW = 1280, kH = 720;

// The distorted position whose undistortion is `u` (fixed-point iteration;
// converges for the small k1 of real lenses).
Eigen::Vector2d DistortRadial(const Eigen::Vector2d& u, double k1) {
  Eigen::Vector2d d = u;
  for (int i = 0; i < 50; ++i) d = u - (UndistortRadial(d, k1, kW, kH) - d);
  return d;
}

// 144 frames (what the estimator holds back) of a pan (turning 0.3 deg a frame) or a sideways traveling
// past points 3..12 units deep, tracks distorted by k1, 0.3 px noise and
// 2 % outliers.
std::vector<FrameTracks> Shot(bool traveling, double k1, unsigned seed) {
  std::mt19937 rng(seed);
  const auto pts = RandomPoints(600, 3, 12, 0.9, seed);
  std::vector<FrameTracks> frames;
  for (int i = 0; i < 144; ++i) {
    SceneCamera cam;
    cam.focal_px = 1000;
    if (traveling)
      cam.center = Eigen::Vector3d(0.04 * i, 0, 0);
    else
      cam.world_from_cam = Eigen::AngleAxisd(0.3 * M_PI / 180 * i, Eigen::Vector3d::UnitY());
    FrameTracks t = MakeFrameTracks(i, 24, cam, pts, kW, kH, 0.3, 0.02, &rng);
    for (TrackPoint& p : t.points) p.px = DistortRadial(p.px, k1);
    frames.push_back(std::move(t));
  }
  return frames;
}

TEST(LensDistortionTest, UndistortionFollowsFfmpegsLenscorrection) {
  const Eigen::Vector2d centre((kW - 1) / 2.0, (kH - 1) / 2.0);
  EXPECT_LT((UndistortRadial(centre, 0.1, kW, kH) - centre).norm(), 1e-12);
  // The corner (r = 1) moves by k1 of its distance from the centre.
  const Eigen::Vector2d corner = centre + Eigen::Vector2d(kW / 2.0, kH / 2.0);
  const Eigen::Vector2d u = UndistortRadial(corner, 0.05, kW, kH);
  EXPECT_NEAR((u - centre).norm(), 1.05 * (corner - centre).norm(), 1e-9);
  EXPECT_EQ(UndistortRadial(corner, 0, kW, kH), corner);
  EXPECT_LT((UndistortRadial(DistortRadial(corner, -0.04), -0.04, kW, kH) - corner).norm(), 1e-6);
}

TEST(LensDistortionTest, FindsK1OnAPan) {
  for (double k1 : {-0.03, 0.05}) {
    const auto e = EstimateRadialDistortion(Shot(false, k1, 7), kW, kH);
    EXPECT_GT(e.pairs, 2);
    // A pan's k1 comes out short: the 8-parameter homography absorbs part
    // of it (measured 0.038 for 0.05).
    EXPECT_NEAR(e.k1, k1, 0.3 * std::abs(k1)) << " k1 " << k1 << " gain " << e.gric_gain
                                              << " penalty " << e.penalty;
  }
}

// The distortion of a 50 deg lens at synth's k1 = -0.04 (x_d = x_n (1 + k1
// r_n^2), r_n in focal units) is 0.04 (half-diagonal / focal)^2 = 0.0115
// here: barely above the floor, yet worth a degree of rotation on footage.
TEST(LensDistortionTest, FindsAMildBarrelOnAPan) {
  const double focal = 0.5 * kW / std::tan(25 * M_PI / 180);
  const double k1 = 0.04 * std::pow(std::hypot(kW, kH) / 2 / focal, 2);
  std::mt19937 rng(5);
  const auto pts = RandomPoints(600, 3, 12, 0.9, 5);
  std::vector<FrameTracks> frames;
  for (int i = 0; i < 60; ++i) {
    SceneCamera cam;
    cam.focal_px = focal;
    cam.world_from_cam = Eigen::AngleAxisd(0.3 * M_PI / 180 * i, Eigen::Vector3d::UnitY());
    FrameTracks t = MakeFrameTracks(i, 24, cam, pts, kW, kH, 0.3, 0.02, &rng);
    for (TrackPoint& p : t.points) p.px = DistortRadial(p.px, k1);
    frames.push_back(std::move(t));
  }
  const auto e = EstimateRadialDistortion(frames, kW, kH);
  EXPECT_NEAR(e.k1, k1, 0.3 * k1) << " best " << e.best_k1 << " gain " << e.gric_gain;
}

// Parallax goes to the fundamental matrix, whose 7 degrees of freedom
// absorb a radial distortion in either direction: a traveling does not
// measure k1 (not even a strong one), it keeps none rather than a wrong one.
TEST(LensDistortionTest, ParallaxDoesNotMeasureIt) {
  for (double k1 : {0.0, 0.05}) {
    const auto e = EstimateRadialDistortion(Shot(true, k1, 7), kW, kH);
    EXPECT_GT(e.pairs, 2);
    EXPECT_EQ(e.k1, 0) << " k1 " << k1 << " best " << e.best_k1 << " gain " << e.gric_gain;
  }
}

// A pinhole camera gets no k1: the noise pays for no extra parameter, and
// parallax goes to the fundamental matrix, not to a distortion.
TEST(LensDistortionTest, PinholeFootageGetsNone) {
  for (bool traveling : {false, true})
    for (unsigned seed : {3u, 4u}) {
      const auto e = EstimateRadialDistortion(Shot(traveling, 0, seed), kW, kH);
      EXPECT_EQ(e.k1, 0) << (traveling ? "traveling" : "pan") << " best " << e.best_k1 << " gain "
                         << e.gric_gain << " penalty " << e.penalty;
    }
}

// Nothing moves (no frame pair), or no frames at all: no evidence, k1 = 0.
TEST(LensDistortionTest, NoMotionNoEstimate) {
  std::mt19937 rng(1);
  const auto pts = RandomPoints(300, 3, 12, 0.9, 1);
  std::vector<FrameTracks> still;
  for (int i = 0; i < 30; ++i) {
    FrameTracks t = MakeFrameTracks(i, 24, SceneCamera{}, pts, kW, kH, 0.3, 0, &rng);
    for (TrackPoint& p : t.points) p.px = DistortRadial(p.px, 0.1);
    still.push_back(std::move(t));
  }
  const auto e = EstimateRadialDistortion(still, kW, kH);
  EXPECT_EQ(e.pairs, 0);
  EXPECT_EQ(e.k1, 0);
  EXPECT_EQ(EstimateRadialDistortion({}, kW, kH).k1, 0);
}

}  // namespace
}  // namespace hapcine
