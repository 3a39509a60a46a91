#include "player/simulate_seat.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "haptics/safety.h"

namespace hapcine {
namespace {

// Centre until 1 s, then the left hand 1 cm to the right until 3 s.
HapticTrack StepTrack() {
  HapticTrack t;
  t.rate_hz = 100;
  t.model = "test";
  t.source = "step";
  for (int i = 0; i <= 300; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    if (s.time_s >= 1.0) s.pos_m[1] = Eigen::Vector3d(0.01, 0, 0);
    t.samples.push_back(s);
  }
  return t;
}

TEST(SimulateSeat, TheGripFollowsAStepWithTheSimsLagAndReturnsToTheCentre) {
  RequestStop();  // left over from an earlier play: must not matter here
  const HapticTrack r = SimulateSeat(StepTrack());
  ClearStopRequest();
  ASSERT_GT(r.samples.size(), 390u);  // 3 s + the 1 s end ramp at 100 Hz
  EXPECT_EQ(r.rate_hz, 100);
  Eigen::Vector3d p[kNumActuators];
  r.Sample(0.9, p);
  EXPECT_LT(p[1].norm(), 2e-4);  // still at the centre before the step
  r.Sample(1.05, p);
  EXPECT_LT(p[1].x(), 0.008);  // the grip lags the step (a mass, not a jump)
  r.Sample(2.9, p);
  // Settled at k/(k + k_hand) of the step (docs/player.md: 9.67 mm).
  EXPECT_NEAR(p[1].x(), 0.00967, 0.0005);
  EXPECT_LT(p[0].norm(), 2e-4);  // head and right hand stay put
  EXPECT_LT(p[2].norm(), 2e-4);
  r.Sample(r.samples.back().time_s, p);
  EXPECT_LT(std::abs(p[1].x()), 0.002);  // the end ramp brought it back
  for (const auto& s : r.samples)
    for (const auto& v : s.pos_m) ASSERT_TRUE(v.allFinite());
}

TEST(SimulateSeat, BadInputIsRejected) {
  HapticTrack empty;
  EXPECT_THROW(SimulateSeat(empty), Error);
  EXPECT_THROW(SimulateSeat(StepTrack(), LoopOptions(), SimDeviceOptions(), 5000), UsageError);
}

}  // namespace
}  // namespace hapcine
