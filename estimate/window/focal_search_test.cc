#include "estimate/window/focal_search.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/rotation.h"

namespace hapcine {
namespace {

constexpr double kPx = 1.0 / 960;  // one pixel at 960 px width, normalised units

// A turning forward move (OpenCV axes: z forward, y down): keyframe k has
// turned by k * `turn_deg` about y and moved 0.3 along its heading.
std::vector<BaCamera> TurningCameras(int n, double turn_deg, double focal) {
  std::vector<BaCamera> cams(n);
  for (int k = 0; k < n; ++k) {
    cams[k].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(k * turn_deg * kPi / 180, Eigen::Vector3d::UnitY()));
    cams[k].log_focal = std::log(focal);
    if (k > 0) cams[k].center = cams[k - 1].center + cams[k - 1].world_from_cam * Eigen::Vector3d(0, 0, 0.3);
  }
  return cams;
}

// Exact normalised observations of points 4-30 units ahead.
std::vector<KeyframeTracks> Observe(const std::vector<BaCamera>& cams, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), depth(4, 30);
  std::vector<KeyframeTracks> tracks(cams.size());
  for (long id = 0; id < 400; ++id) {
    const double z = depth(rng);
    const Eigen::Vector3d X(u(rng) * z, 0.3 * u(rng) * z, z);
    for (size_t k = 0; k < cams.size(); ++k) {
      const Eigen::Vector3d p = cams[k].world_from_cam.conjugate() * (X - cams[k].center);
      if (p.z() < 0.5) continue;
      const Eigen::Vector2d uv = std::exp(cams[k].log_focal) * p.head<2>() / p.z();
      if (uv.cwiseAbs().maxCoeff() < 0.5) tracks[k][id] = uv;
    }
  }
  return tracks;
}

TEST(FocalSearch, ChainAtTheTrueFocalRecoversTheTurn) {
  const std::vector<BaCamera> truth = TurningCameras(6, 2.0, 0.6);
  const std::vector<KeyframeTracks> tracks = Observe(truth, 3);
  std::vector<WindowKeyframe> kf(truth.size());
  for (size_t k = 0; k < kf.size(); ++k) {
    kf[k].pos = static_cast<int>(k);
    kf[k].model = k == 0 ? MotionModel::kStatic : MotionModel::kGeneral;
    kf[k].fixed = kf[k].chain_start = k == 0;
    kf[k].tracks = &tracks[k];
    kf[k].cam.log_focal = std::log(1.07);  // the chain was built at a 50 degree prior
  }
  // At the prior the turn comes out short; rebuilt at the true focal it is exact.
  const std::vector<BaCamera> right = ChainAtFocal(kf, std::log(0.6 / 1.07), {}, 10);
  const std::vector<BaCamera> wrong = ChainAtFocal(kf, 0, {}, 10);
  const double turn_right = AngleBetweenDeg(right.back().world_from_cam, right.front().world_from_cam);
  const double turn_wrong = AngleBetweenDeg(wrong.back().world_from_cam, wrong.front().world_from_cam);
  EXPECT_NEAR(turn_right, 10.0, 0.05);
  EXPECT_LT(turn_wrong, 8.0);
  EXPECT_NEAR(std::exp(right.back().log_focal), 0.6, 1e-9);
  // The heading of the move, up to scale.
  const Eigen::Vector3d step = right[1].center - right[0].center;
  EXPECT_GT(step.normalized().z(), 0.999);
}

TEST(FocalSearch, ChainKeepsHeldKeyframesAndFailedIntervals) {
  const std::vector<BaCamera> truth = TurningCameras(3, 2.0, 0.6);
  const std::vector<KeyframeTracks> empty(3);
  std::vector<WindowKeyframe> kf(3);
  for (int k = 0; k < 3; ++k) {
    kf[k].cam = truth[k];
    kf[k].model = MotionModel::kGeneral;
    kf[k].tracks = &empty[k];  // no matches: every fit fails
  }
  kf[1].fixed = true;
  const std::vector<BaCamera> c = ChainAtFocal(kf, 0.2, {}, 10);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((c[k].center - truth[k].center).norm(), 1e-9);
    EXPECT_LT(AngleBetweenDeg(c[k].world_from_cam, truth[k].world_from_cam), 1e-6);
    EXPECT_NEAR(c[k].log_focal, truth[k].log_focal + 0.2, 1e-12);
  }
}

TEST(FocalSearch, BestStartNeedsEvidenceAgainstThePrior) {
  std::vector<double> prior(1000, 0.5 * kPx), slightly(1000, 0.5 * kPx), much(1000, 0.5 * kPx);
  for (int i = 0; i < 5; ++i) slightly[i] = 0.45 * kPx;  // a gain of well under ln(2m)
  for (int i = 0; i < 300; ++i) prior[i] = 3 * kPx;      // the prior's solve stopped in a worse minimum
  EXPECT_EQ(BestFocalStart({much, slightly}, 0.25 * kPx), 0);
  EXPECT_EQ(BestFocalStart({prior, slightly, much}, 0.25 * kPx), 1);  // the lowest chi2 of those that beat it
  std::vector<double> failed(1000, HUGE_VAL);
  EXPECT_EQ(BestFocalStart({prior, failed}, 0.25 * kPx), 0);
  EXPECT_EQ(BestFocalStart({}, 0.25 * kPx), 0);
}

TEST(FocalSearch, StartsAreTheCurrentFocalAndHalfAnOctaveEitherWay) {
  const std::vector<double> s = FocalStartShifts();
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0], 0.0);
  EXPECT_NEAR(std::exp(s[2]) / std::exp(s[1]), 2.0, 1e-12);
}

}  // namespace
}  // namespace hapcine
