#include "platform/platform_safety.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "platform/platform_track.h"

namespace hapcine {
namespace {

PlatformConfig Load(const char* name) {
  return LoadPlatformFile(std::string(HAPCINE_SOURCE_DIR) + "/haptics/" + name);
}

// Runs targets through the clamp and measures the result.
PlatformLimitCheck ClampAndMeasure(const PlatformConfig& cfg, const std::vector<PlatformPose>& targets,
                       SafetyCounts* counts = nullptr) {
  PlatformSafety safety(cfg, cfg.rate_hz);
  PlatformTrack track;
  track.rate_hz = cfg.rate_hz;
  for (size_t i = 0; i < targets.size(); ++i) {
    PlatformSample s;
    s.time_s = i / cfg.rate_hz;
    s.pose = safety.Step(targets[i]);
    track.samples.push_back(s);
  }
  if (counts) *counts = safety.counts();
  return MeasurePlatformLimits(track, cfg);
}

std::vector<PlatformPose> Adversarial(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PlatformPose> out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 3000; ++i) {
    PlatformPose p;
    for (int d = 0; d < kNumDofs; ++d) p[d] = u(rng);
    if (i % 500 < 100) p *= 1e6;                   // huge jumps
    if (i % 500 >= 100 && i % 500 < 200) p = PlatformPose::Constant(i % 2 ? 1e6 : -1e6);  // bang-bang
    if (i % 97 == 0) p[i % kNumDofs] = nan;        // non-finite targets
    if (i % 500 >= 400) p.setZero();               // back home
    out.push_back(p);
  }
  return out;
}

TEST(PlatformSafety, LimitsHoldOnAdversarialTargets) {
  for (const char* file : {"platform_3dof.json", "platform_stewart.json"}) {
    const PlatformConfig cfg = Load(file);
    SafetyCounts counts;
    const PlatformLimitCheck c = ClampAndMeasure(cfg, Adversarial(5), &counts);
    EXPECT_TRUE(c.finite) << file;
    EXPECT_LE(c.position_ratio, 1 + 1e-9) << file;
    EXPECT_LE(c.velocity_ratio, 1 + 1e-9) << file;
    EXPECT_EQ(c.disabled_max, 0.0) << file;
    EXPECT_TRUE(c.legs_in_stroke) << file;
    EXPECT_GT(counts.nonfinite, 0u) << file;
    EXPECT_GT(counts.clamped, 1000u) << file;
    if (counts.stroke_limited == 0) {
      EXPECT_LE(c.acceleration_ratio, 1 + 1e-9) << file;
    }
  }
}

TEST(PlatformSafety, AccelerationHoldsWithoutLegLimits) {
  PlatformConfig cfg = Load("platform_stewart.json");
  cfg.stewart.reset();
  const PlatformLimitCheck c = ClampAndMeasure(cfg, Adversarial(9));
  EXPECT_LE(c.position_ratio, 1 + 1e-9);
  EXPECT_LE(c.velocity_ratio, 1 + 1e-9);
  EXPECT_LE(c.acceleration_ratio, 1 + 1e-9);
}

TEST(PlatformSafety, ReachesAReachableTargetExactly) {
  const PlatformConfig cfg = Load("platform_3dof.json");
  PlatformPose target = PlatformPose::Zero();
  target[1] = 0.02;  // 2 cm of heave, inside the 4 cm limit
  PlatformSafety safety(cfg, cfg.rate_hz);
  PlatformPose p;
  for (int i = 0; i < 200; ++i) p = safety.Step(target);
  EXPECT_NEAR(p[1], 0.02, 1e-12);
}

TEST(PlatformSafety, BrakingSpeedStopsWithinTheDistance) {
  // Moving at the bound and then braking by at most a dt per sample, each
  // time as fast as the bound allows, never passes the end.
  for (double d : {0.0, 1e-6, 3e-4, 0.01, 0.3}) {
    const double a = 3, dt = 0.01;
    double v = BrakingSpeed(d, a, dt), left = d;
    for (int i = 0; i < 1000 && v > 0; ++i) {
      left -= v * dt;
      ASSERT_GE(left, -1e-15) << d;
      const double next = BrakingSpeed(left, a, dt);
      ASSERT_GE(next, v - a * dt - 1e-12) << d;  // the decrement needed stays within a dt
      v = std::min(next, v);
    }
    EXPECT_GT(BrakingSpeed(0.3, a, dt), BrakingSpeed(0.01, a, dt));
  }
}

TEST(PlatformSafety, VerifyRejectsATrackBeyondTheLimits) {
  const PlatformConfig cfg = Load("platform_3dof.json");
  PlatformTrack track;
  track.rate_hz = cfg.rate_hz;
  PlatformSample s;
  track.samples.push_back(s);
  s.time_s = 0.01;
  s.pose[1] = 0.001;  // 0.1 m/s: within 0.2 m/s
  track.samples.push_back(s);
  EXPECT_NO_THROW(VerifyPlatformTrack(track, cfg));
  track.samples.back().pose[1] = 0.01;  // 1 m/s
  EXPECT_THROW(VerifyPlatformTrack(track, cfg), Error);
  track.samples.back().pose[1] = 0;
  track.samples.back().pose[0] = 1e-3;  // sway: a 3-DOF seat has none
  EXPECT_THROW(VerifyPlatformTrack(track, cfg), Error);
}

}  // namespace
}  // namespace hapcine
