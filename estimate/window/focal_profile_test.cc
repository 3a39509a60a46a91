#include "estimate/window/focal_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimate/window/window_test_scene.h"

namespace hapcine {
namespace {

using window_test::kFocal;
using window_test::TestWindow;

// A window of 8 keyframes turning by `turn_deg` per keyframe, and points
// 4-30 units ahead seen by them with Gaussian noise of `noise_px`, solved
// from the truth.
TestWindow SolvedWindow(double turn_deg, double noise_px, unsigned seed) {
  TestWindow w;
  w.cams = window_test::MovingCameras(8, turn_deg);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), depth(4, 30);
  std::normal_distribution<double> noise(0, noise_px * window_test::kPx);
  for (int id = 0; id < 300; ++id) {
    const double z = depth(rng);
    const Eigen::Vector3d X(u(rng) * z, 0.3 * u(rng) * z, z);
    const int point = static_cast<int>(w.points.size());
    std::vector<BaObservation> track;
    for (size_t k = 0; k < w.cams.size(); ++k) {
      const std::optional<Eigen::Vector2d> uv = window_test::SeenAt(w.cams[k], X);
      if (!uv) continue;
      const Eigen::Vector2d error(noise(rng), noise(rng));
      track.push_back(window_test::Observation(static_cast<int>(k), point, *uv + error));
    }
    window_test::AddPoint(X, track, &w);
  }
  w.ba = window_test::WindowOptions(w.cams);
  EXPECT_TRUE(SolveBundle(&w.cams, &w.points, w.obs, w.ba).success);
  return w;
}

FocalProfile ProfileOf(const TestWindow& w) {
  return ProfileFocal(w.ba, w.cams, w.points, w.obs, DefaultFocalProfileShifts());
}

TEST(FocalProfile, ParabolaIsRecoveredExactly) {
  double a = 0, b = 0, c = 0;
  const auto y = [](double x) { return 3 * x * x - 2 * x + 1; };
  ASSERT_TRUE(FitParabola({-2, -1, 0, 1, 2}, {y(-2), y(-1), y(0), y(1), y(2)}, &a, &b, &c));
  EXPECT_NEAR(a, 3, 1e-9);
  EXPECT_NEAR(b, -2, 1e-9);
  EXPECT_NEAR(c, 1, 1e-9);
}

TEST(FocalProfile, ParabolaNeedsThreeDistinctFinitePoints) {
  double a = 0, b = 0, c = 0;
  EXPECT_FALSE(FitParabola({0, 1}, {0, 1}, &a, &b, &c));
  EXPECT_FALSE(FitParabola({1, 1, 1}, {1, 2, 3}, &a, &b, &c));
  EXPECT_FALSE(FitParabola({0, 1, 2}, {0, NAN, 4}, &a, &b, &c));
  EXPECT_TRUE(FitParabola({0, 1, 2, 3}, {0, NAN, 4, 9}, &a, &b, &c));
  EXPECT_NEAR(a, 1, 1e-9);
}

// A turning, translating window pins its focal: the profile's minimum is at
// the solution and the truth lies within a few standard errors.
TEST(FocalProfile, TurningWindowPinsTheFocal) {
  const TestWindow w = SolvedWindow(3.0, 1.0, 5);
  const FocalProfile prof = ProfileOf(w);
  ASSERT_EQ(prof.chi2.size(), DefaultFocalProfileShifts().size());
  ASSERT_EQ(prof.errors.size(), prof.chi2.size());
  for (const auto& e : prof.errors) EXPECT_EQ(e.size(), w.obs.size());
  ASSERT_TRUE(std::isfinite(prof.sigma_log_focal));
  EXPECT_GT(prof.sigma_log_focal, 1e-4);
  EXPECT_LT(prof.sigma_log_focal, 0.02);
  EXPECT_NEAR(prof.minimum_log_shift, 0, prof.sigma_log_focal);
  const double error = std::abs(w.cams[0].log_focal - std::log(kFocal));
  EXPECT_LT(error, 4 * prof.sigma_log_focal);
}

// The standard error follows the noise: twice the noise, about twice the
// sigma (chi2 is in units of the window's own residual variance).
TEST(FocalProfile, SigmaGrowsWithTheNoise) {
  const double low = ProfileOf(SolvedWindow(3.0, 0.5, 7)).sigma_log_focal;
  const double high = ProfileOf(SolvedWindow(3.0, 1.0, 7)).sigma_log_focal;
  EXPECT_GT(high / low, 1.5);
  EXPECT_LT(high / low, 2.7);
}

// Without rotation the focal is not observable from a translating window
// (scaling every point's and centre's x, y absorbs it): a flat profile.
TEST(FocalProfile, TranslationWithoutTurnDoesNotPinTheFocal) {
  const FocalProfile turning = ProfileOf(SolvedWindow(3.0, 1.0, 9));
  const FocalProfile straight = ProfileOf(SolvedWindow(0.0, 1.0, 9));
  EXPECT_GT(straight.sigma_log_focal, 10 * turning.sigma_log_focal);
}

}  // namespace
}  // namespace hapcine
