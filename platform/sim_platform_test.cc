#include "platform/sim_platform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace hapcine {
namespace {

PlatformTrack Step(double heave_m, double seconds) {
  PlatformTrack t;
  for (int i = 0; i <= seconds * 100; ++i) {
    PlatformSample s;
    s.time_s = i / 100.0;
    s.pose[1] = i > 0 ? heave_m : 0.0;
    t.samples.push_back(s);
  }
  return t;
}

TEST(SimPlatform, AStepLagsOvershootsAndSettles) {
  const PlatformTrack sim = SimulatePlatform(Step(0.02, 3));
  ASSERT_EQ(sim.samples.size(), 301u);
  double peak = 0;
  for (const auto& s : sim.samples) peak = std::max(peak, s.pose[1]);
  // Damping 0.7: overshoot exp(-pi z / sqrt(1 - z^2)) = 4.6 %.
  EXPECT_NEAR(peak, 0.02 * 1.046, 0.02 * 0.01);
  EXPECT_LT(sim.samples[5].pose[1], 0.01);  // 50 ms after the step: still lagging
  EXPECT_NEAR(sim.samples.back().pose[1], 0.02, 1e-5);
}

TEST(SimPlatform, RejectsBadOptions) {
  SimPlatformOptions o;
  o.damping = 0;
  EXPECT_THROW(SimulatePlatform(Step(0.01, 1), o), UsageError);
  o = SimPlatformOptions();
  o.step_hz = 5;
  EXPECT_THROW(SimulatePlatform(Step(0.01, 1), o), UsageError);
  EXPECT_TRUE(SimulatePlatform(PlatformTrack()).samples.empty());
}

}  // namespace
}  // namespace hapcine
