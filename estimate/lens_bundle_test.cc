#include "estimate/lens_bundle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hapcine {
namespace {

constexpr int kW = 320, kH = 180;

// The observed (distorted) position whose undistortion (lens_distortion.h's
// model, normalised by the width) is `u`: fixed-point iteration.
Eigen::Vector2d Distort(const Eigen::Vector2d& u, double k1) {
  const double half_diagonal = 0.5 * std::hypot(kW, kH);
  const double r2_per_u2 = (kW / half_diagonal) * (kW / half_diagonal);
  Eigen::Vector2d d = u;
  for (int i = 0; i < 50; ++i) d = u / (1 + k1 * r2_per_u2 * d.squaredNorm());
  return d;
}

enum class Move { kTraveling, kCrane, kPan, kStatic };

// A window of 12 keyframes of a 50 deg lens (OpenCV axes) moving as `move`
// past 400 points 3..12 units deep, observed through k1 with `noise_px`
// Gaussian noise (pixels of a 320 px frame). The cameras and points start
// where a pinhole solve would leave them nearby: the truth, slightly off.
// `focal_error`: the window's focal is the true one x this (a wrong prior).
SolvedWindow Window(Move move, double k1, double noise_px, unsigned seed, double focal_error = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1, 1), depth(3, 12);
  std::normal_distribution<double> noise(0, noise_px / kW), jitter(0, 1e-3);
  const double focal = 0.5 / std::tan(25 * M_PI / 180);  // normalised by the width
  SolvedWindow w;
  w.use_depth = move != Move::kPan;
  for (int i = 0; i < 12; ++i) {
    BaCamera cam;
    cam.log_focal = std::log(focal);
    if (move == Move::kTraveling) cam.center = Eigen::Vector3d(0.15 * i, 0, 0);
    if (move == Move::kCrane) cam.center = Eigen::Vector3d(0.05 * i, -0.12 * i, 0.02 * i);
    if (move == Move::kPan || move == Move::kCrane)
      cam.world_from_cam = Eigen::AngleAxisd(0.02 * i, Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitX());
    if (i == 0) cam.fixed = true;
    w.cameras.push_back(cam);
  }
  std::vector<Eigen::Vector3d> truth;
  for (int j = 0; j < 400; ++j) {
    const double z = depth(rng);
    truth.emplace_back(uni(rng) * 0.9 * z + 0.6, uni(rng) * 0.55 * z - 0.4, z);
  }
  for (int j = 0; j < static_cast<int>(truth.size()); ++j) {
    bool seen = false;
    for (int i = 0; i < 12; ++i) {
      const BaCamera& cam = w.cameras[i];
      const Eigen::Vector3d p = cam.world_from_cam.conjugate() * (truth[j] - cam.center);
      const Eigen::Vector2d u = focal * p.head<2>() / p.z();
      if (p.z() <= 0 || std::abs(u.x()) > 0.5 || std::abs(u.y()) > 0.5 * kH / kW) continue;
      const Eigen::Vector2d n(noise(rng), noise(rng));
      w.observations.push_back({i, static_cast<int>(w.points.size()), Distort(u, k1) + n});
      seen = true;
    }
    if (!seen) continue;
    BaPoint pt;  // anchor at the origin: X = d / rho
    const Eigen::Vector3d X = truth[j] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)) * 10;
    pt.homogeneous << (w.use_depth ? X : X.normalized()), w.use_depth ? 1 : 0;
    pt.homogeneous.normalize();
    w.points.push_back(pt);
  }
  for (BaCamera& cam : w.cameras) cam.log_focal += std::log(focal_error);
  for (size_t i = 1; i < w.cameras.size(); ++i)
    w.cameras[i].world_from_cam = w.cameras[i].world_from_cam *
                                  Eigen::AngleAxisd(jitter(rng), Eigen::Vector3d::UnitZ());
  return w;
}

TEST(LensBundleTest, TravelingFindsAStrongLens) {
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kTraveling, 0.05, 0.3, 1), kW, kH);
  ASSERT_TRUE(e.solved);
  EXPECT_NEAR(e.k1, 0.05, 0.01);
  EXPECT_GT(e.chi2_gain, e.penalty);
}

TEST(LensBundleTest, TravelingFindsTheTestLooksLens) {
  // synth --distortion -0.04 at 50 deg is k1 = +0.0115 in our convention.
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kTraveling, 0.0115, 0.3, 1), kW, kH);
  EXPECT_NEAR(e.best_k1, 0.0115, 0.003);
}

TEST(LensBundleTest, CraneFindsAPincushion) {
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kCrane, -0.03, 0.3, 2), kW, kH);
  EXPECT_NEAR(e.k1, -0.03, 0.004);
}

TEST(LensBundleTest, PanFindsTheLensOnBearings) {
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kPan, 0.05, 0.3, 3), kW, kH);
  EXPECT_NEAR(e.k1, 0.05, 0.005);
}

TEST(LensBundleTest, PinholeKeepsNone) {
  for (unsigned seed = 4; seed < 6; ++seed) {
    const LensBundleEstimate t = EstimateK1InWindow(Window(Move::kTraveling, 0, 0.3, seed), kW, kH);
    EXPECT_TRUE(t.solved);
    EXPECT_EQ(t.k1, 0) << "traveling, seed " << seed << ": best " << t.best_k1;
    const LensBundleEstimate c = EstimateK1InWindow(Window(Move::kCrane, 0, 0.3, seed), kW, kH);
    EXPECT_EQ(c.k1, 0) << "crane, seed " << seed << ": best " << c.best_k1;
  }
}

TEST(LensBundleTest, AWrongFocalIsNoLens) {
  // A focal held 10 % off (an unobservable focal at its prior) bends a
  // rotation's tracks radially: the focal factor takes it, not k1.
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kPan, 0, 0.3, 11, 1.1), kW, kH);
  EXPECT_TRUE(e.solved);
  EXPECT_EQ(e.k1, 0) << "best " << e.best_k1;
  EXPECT_NEAR(EstimateK1InWindow(Window(Move::kPan, 0.03, 0.3, 12, 0.9), kW, kH).k1, 0.03, 0.005);
}

TEST(LensBundleTest, NoiseHidesAWeakLens) {
  // 0.004 moves the corner under a pixel of a 320 px frame: under 2 px noise
  // it is no finding.
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kTraveling, 0.004, 2.0, 8), kW, kH);
  EXPECT_EQ(e.k1, 0);
}

TEST(LensBundleTest, StaticCameraMeasuresNothing) {
  // Every view the same: each point's bearing absorbs any distortion.
  const LensBundleEstimate e = EstimateK1InWindow(Window(Move::kStatic, 0.05, 0.3, 9), kW, kH);
  EXPECT_EQ(e.k1, 0);
}

TEST(LensBundleTest, TooLittleToSolve) {
  SolvedWindow w = Window(Move::kTraveling, 0.05, 0.3, 10);
  w.cameras.resize(2);
  EXPECT_FALSE(EstimateK1InWindow(w, kW, kH).solved);
  EXPECT_FALSE(EstimateK1InWindow(SolvedWindow{}, kW, kH).solved);
}

// Several windows of one shot (lens_bundle.h EstimateK1InWindows).

TEST(LensBundleTest, TwoWindowsThatAgreeKeepTheLens) {
  const LensAgreement a = EstimateK1InWindows(
      {Window(Move::kPan, 0.03, 0.3, 21), Window(Move::kCrane, 0.03, 0.3, 22)}, kW, kH);
  EXPECT_EQ(a.significant, 2);
  EXPECT_TRUE(a.same_sign);
  EXPECT_LE(a.spread_chi2, a.spread_limit);
  EXPECT_NEAR(a.k1, 0.03, 0.004);
  EXPECT_GT(a.sigma, 0);
}

TEST(LensBundleTest, OneWindowAloneIsNotConfirmed) {
  // Its own test keeps k1, but no other window was there to confirm it.
  const SolvedWindow w = Window(Move::kPan, 0.03, 0.3, 23);
  EXPECT_NE(EstimateK1InWindow(w, kW, kH).k1, 0);
  const LensAgreement a = EstimateK1InWindows({w}, kW, kH);
  EXPECT_TRUE(a.windows.empty());  // one window cannot make two that pay: not measured
  EXPECT_EQ(a.k1, 0);
}

TEST(LensBundleTest, ABendInOneWindowOnlyIsNoLens) {
  // Something that bends one window's tracks radially (drift, a subject)
  // and not the next window's: not the lens, which is in both.
  const LensAgreement a = EstimateK1InWindows(
      {Window(Move::kPan, 0.03, 0.3, 24), Window(Move::kPan, 0, 0.3, 25)}, kW, kH);
  EXPECT_NE(a.windows[0].k1, 0);
  EXPECT_EQ(a.k1, 0) << "pooled " << a.pooled_k1 << " spread " << a.spread_chi2;
}

TEST(LensBundleTest, WindowsOfOppositeSignsAreNoLens) {
  const LensAgreement a = EstimateK1InWindows(
      {Window(Move::kPan, 0.03, 0.3, 26), Window(Move::kCrane, -0.03, 0.3, 27)}, kW, kH);
  EXPECT_EQ(a.significant, 2);
  EXPECT_FALSE(a.same_sign);
  EXPECT_EQ(a.k1, 0);
}

TEST(LensBundleTest, AWrongFocalInEveryWindowIsNoLens) {
  // A focal held 10 % off in both windows: the focal factor takes it, no
  // window pays for a k1, none is kept.
  const LensAgreement a = EstimateK1InWindows(
      {Window(Move::kPan, 0, 0.3, 28, 1.1), Window(Move::kPan, 0, 0.3, 29, 1.1)}, kW, kH);
  EXPECT_EQ(a.k1, 0) << "pooled " << a.pooled_k1;
}

TEST(LensBundleTest, PinholeWindowsKeepNone) {
  const LensAgreement a = EstimateK1InWindows(
      {Window(Move::kTraveling, 0, 0.3, 30), Window(Move::kCrane, 0, 0.3, 31), Window(Move::kPan, 0, 0.3, 32)},
      kW, kH);
  // The third is measured only if one of the first two paid.
  EXPECT_EQ(a.windows.size(), a.significant > 0 ? 3u : 2u);
  EXPECT_EQ(a.k1, 0) << "pooled " << a.pooled_k1;
}

}  // namespace
}  // namespace hapcine
