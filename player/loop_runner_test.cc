#include "player/loop_runner.h"

#include <gtest/gtest.h>

#include "haptics/sim_device.h"

namespace hapcine {
namespace {

// The one real-thread test: a 0.3 s track on the sim, played by the 1 kHz
// thread against the wall clock. Loose bounds: this checks the plumbing
// (thread, sleeps, finish, zero force), not timing (see bench/).
TEST(LoopRunner, RealThreadSmokeTest) {
  ClearStopRequest();
  HapticTrack track;
  for (int i = 0; i <= 30; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    s.pos_m[0] = Eigen::Vector3d(0.01, 0, 0);
    track.samples.push_back(s);
  }
  HapSeat seat;
  for (auto& d : seat.devices) {
    d = std::make_unique<SimDevice>();
    d->Open();
  }
  WallClock clock(0.3);
  LoopOptions o;
  o.start_ramp_s = 0.1;
  o.end_ramp_s = 0.1;
  HapticLoop loop(track, seat, clock, o);
  RunnerOptions ro;
  ro.max_run_s = 3;  // safety net only
  int progress_calls = 0;
  const RunReport r = RunLoop(
      loop, ro, nullptr, [&] { ++progress_calls; }, 0.05);
  EXPECT_FALSE(r.error);
  EXPECT_EQ(loop.status(), LoopStatus::kFinished);
  EXPECT_GT(loop.stats().ticks, 100);
  EXPECT_LT(r.elapsed_s, 2.5);
  EXPECT_GT(progress_calls, 0);
  EXPECT_GT(loop.stats().sync_error.count(), 0);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(static_cast<SimDevice&>(*seat.devices[a]).last_force_n(), Eigen::Vector3d::Zero());
}

TEST(LoopRunner, CancelFlagStopsTheThread) {
  ClearStopRequest();
  HapticTrack track;
  for (int i = 0; i <= 100; ++i) {
    HapticSample s;
    s.time_s = i;
    track.samples.push_back(s);
  }
  HapSeat seat;
  seat.devices[0] = std::make_unique<SimDevice>();
  seat.devices[0]->Open();
  WallClock clock(100);
  HapticLoop loop(track, seat, clock, LoopOptions());
  std::atomic<bool> cancel{true};
  RunnerOptions ro;
  ro.realtime = false;
  const RunReport r = RunLoop(loop, ro, &cancel);
  EXPECT_EQ(loop.stats().ticks, 0);
  EXPECT_EQ(r.realtime_note, "real-time scheduling not requested");
}

}  // namespace
}  // namespace hapcine
