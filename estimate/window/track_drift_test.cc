#include "estimate/window/track_drift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "estimate/window/window_test_scene.h"

namespace hapcine {
namespace {

using window_test::kFocal;
using window_test::kPx;
constexpr int kFramesPerKeyframe = 5;

TEST(ObservationAgesTest, FramesSinceThePointsEarliestObservation) {
  using window_test::Observation;
  const std::vector<BaObservation> obs = {Observation(1, 0), Observation(2, 0), Observation(0, 1),
                                          Observation(2, 1), Observation(3, 0)};
  const std::vector<int> pos = {10, 15, 22, 30};
  EXPECT_EQ(ObservationAges(obs, pos), (std::vector<int>{0, 7, 0, 12, 15}));
}

TEST(FitDriftTest, RecoversAGrowthThatIsThere) {
  std::mt19937 rng(3);
  std::vector<double> e;
  std::vector<int> ages;
  for (int i = 0; i < 4000; ++i) {
    const int age = i % 40;
    std::normal_distribution<double> n(0, std::sqrt(0.25 + 0.04 * age));  // s0 = 0.5, q^2 = 0.04
    e.push_back(std::hypot(n(rng), n(rng)) / std::sqrt(2.0));
    ages.push_back(age);
  }
  const DriftFit fit = FitDrift(e, ages);
  EXPECT_TRUE(fit.significant);
  EXPECT_NEAR(fit.s0_sq, 0.25, 0.05);
  EXPECT_NEAR(fit.q_sq, 0.04, 0.008);
}

TEST(FitDriftTest, NoGrowthIsNotSignificantAndLeavesTheWeights) {
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0, 0.5);
  std::vector<double> e;
  std::vector<int> ages;
  for (int i = 0; i < 4000; ++i) {
    e.push_back(n(rng));
    ages.push_back(i % 40);
  }
  const DriftFit fit = FitDrift(e, ages);
  EXPECT_FALSE(fit.significant);
  std::vector<BaObservation> obs(e.size());
  EXPECT_FALSE(ApplyDriftWeights(fit, ages, &obs));
  for (const auto& o : obs) EXPECT_EQ(o.noise_scale, 1.0);
}

TEST(FitDriftTest, DegenerateInputs) {
  EXPECT_FALSE(FitDrift({}, {}).significant);
  EXPECT_FALSE(FitDrift({1, 2, 3, 4}, {5, 5, 5, 5}).significant);  // one age: nothing to fit
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  const DriftFit fit = FitDrift({inf, nan, 1, 2}, {0, 1, 2, 3});  // non-finite skipped: two left
  EXPECT_EQ(fit.observations, 2);
  EXPECT_FALSE(fit.significant);
}

TEST(ApplyDriftWeightsTest, SigmaOfAgeOverSigmaAtZero) {
  DriftFit fit;
  fit.s0_sq = 0.25;
  fit.q_sq = 0.05;
  fit.significant = true;
  std::vector<BaObservation> obs(3);
  ASSERT_TRUE(ApplyDriftWeights(fit, {0, 5, 15}, &obs));
  EXPECT_DOUBLE_EQ(obs[0].noise_scale, 1.0);
  EXPECT_DOUBLE_EQ(obs[1].noise_scale, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(obs[2].noise_scale, 2.0);
}

// A translating, turning window of 12 keyframes (5 frames apart). Each
// track is followed from its first keyframe with a KLT-like error: matching
// noise `s0_px` plus a random walk of `q_px` per sqrt(frame) started there.
struct Window : window_test::TestWindow {
  std::vector<int> pos;  // each keyframe's frame
};

Window DriftingWindow(double s0_px, double q_px, unsigned seed) {
  Window w;
  const int n = 12;
  w.cams = window_test::MovingCameras(n, 1.5);
  for (int k = 0; k < n; ++k) w.pos.push_back(k * kFramesPerKeyframe);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), depth(4, 30);
  std::uniform_int_distribution<int> start(0, n - 3);
  std::normal_distribution<double> unit(0, 1);
  const double step = q_px * kPx * std::sqrt(double(kFramesPerKeyframe));  // the walk per keyframe
  for (int id = 0; id < 300; ++id) {
    const double z = depth(rng);
    const int first = start(rng);
    const Eigen::Vector3d in_first(u(rng) * z * 0.8, 0.3 * u(rng) * z, z);  // first keyframe's axes
    const Eigen::Vector3d X = w.cams[first].center + w.cams[first].world_from_cam * in_first;
    const int point = static_cast<int>(w.points.size());
    Eigen::Vector2d walk = Eigen::Vector2d::Zero();
    std::vector<BaObservation> track;
    for (int k = first; k < n; ++k) {
      const std::optional<Eigen::Vector2d> uv = window_test::SeenAt(w.cams[k], X);
      if (!uv) break;  // a lost track is not found again
      if (!track.empty()) walk += step * Eigen::Vector2d(unit(rng), unit(rng));
      const Eigen::Vector2d noise = s0_px * kPx * Eigen::Vector2d(unit(rng), unit(rng));
      track.push_back(window_test::Observation(k, point, *uv + walk + noise));
    }
    window_test::AddPoint(X, track, &w);
  }
  w.ba = window_test::WindowOptions(w.cams);
  return w;
}

struct FocalErrors {
  double unweighted_sq = 0, weighted_sq = 0;
  int significant = 0;
};

// Over `seeds` windows: the focal's squared log error solved with every
// observation alike, and after weighting by the drift the residuals show.
FocalErrors SolveBothWays(double s0_px, double q_px, int seeds) {
  FocalErrors r;
  for (int seed = 1; seed <= seeds; ++seed) {
    Window w = DriftingWindow(s0_px, q_px, seed);
    EXPECT_TRUE(SolveBundle(&w.cams, &w.points, w.obs, w.ba).success);
    const double before = w.cams[0].log_focal - std::log(kFocal);
    r.unweighted_sq += before * before;
    const std::vector<int> ages = ObservationAges(w.obs, w.pos);
    const DriftFit fit = FitDrift(ObservationErrors(w.cams, w.points, w.obs, true), ages);
    r.significant += fit.significant;
    if (ApplyDriftWeights(fit, ages, &w.obs)) {
      EXPECT_TRUE(SolveBundle(&w.cams, &w.points, w.obs, w.ba).success);
    }
    const double after = w.cams[0].log_focal - std::log(kFocal);
    r.weighted_sq += after * after;
  }
  return r;
}

TEST(DriftWeightsTest, NoDriftTheSolveIsUnchanged) {
  const FocalErrors r = SolveBothWays(0.5, 0.0, 6);
  EXPECT_EQ(r.significant, 0);
  EXPECT_EQ(r.weighted_sq, r.unweighted_sq);
}

}  // namespace
}  // namespace hapcine
