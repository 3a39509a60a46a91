#include "player/media_clock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <thread>

namespace hapcine {
namespace {

TEST(MediaClock, ExtrapolatesWhilePlayingAndHoldsWhilePaused) {
  ClockReading r;
  r.media_s = 10;
  r.wall_s = 100;
  r.rate = 1.5;
  r.valid = true;
  r.paused = false;
  EXPECT_DOUBLE_EQ(Extrapolate(r, 100.2), 10.3);
  EXPECT_DOUBLE_EQ(Extrapolate(r, 99.0), 10.0);        // never backwards
  EXPECT_DOUBLE_EQ(Extrapolate(r, 150.0, 1.0), 11.5);  // bounded horizon
  r.paused = true;
  EXPECT_DOUBLE_EQ(Extrapolate(r, 100.2), 10.0);
  r.paused = false;
  r.valid = false;
  EXPECT_DOUBLE_EQ(Extrapolate(r, 100.2), 10.0);
  r.valid = true;
  EXPECT_DOUBLE_EQ(Extrapolate(r, std::nan("")), 10.0);
}

TEST(MediaClock, ClockCellNeverTearsAReading) {
  ClockCell cell;
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    ClockReading r;
    for (uint64_t i = 1; !stop.load(); ++i) {
      r.serial = i;
      r.media_s = static_cast<double>(i);
      r.wall_s = 2.0 * static_cast<double>(i);
      r.seek_serial = i * 3;
      r.paused = i % 2;
      r.valid = true;
      cell.Store(r);
    }
  });
  int64_t torn = 0;
  for (int k = 0; k < 200000; ++k) {
    const ClockReading r = cell.Load();
    if (r.serial == 0) continue;
    const double i = static_cast<double>(r.serial);
    if (r.media_s != i || r.wall_s != 2 * i || r.seek_serial != r.serial * 3 ||
        r.paused != (r.serial % 2 == 1))
      ++torn;
  }
  stop = true;
  writer.join();
  EXPECT_EQ(torn, 0);
}

TEST(MediaClock, WallClockRunsFromStartAndEnds) {
  WallClock c(2.0);
  c.Start(SteadySeconds() - 0.5);
  ClockReading r = c.Read();
  EXPECT_TRUE(r.valid);
  EXPECT_FALSE(r.paused);
  EXPECT_NEAR(r.media_s, 0.5, 0.05);
  EXPECT_FALSE(r.eof);
  c.Start(SteadySeconds() - 3);
  r = c.Read();
  EXPECT_TRUE(r.eof);
  EXPECT_DOUBLE_EQ(r.media_s, 2.0);
  double t = 0;
  ASSERT_TRUE(c.TrueMediaTime(SteadySeconds(), &t));
  EXPECT_NEAR(t, 3.0, 0.05);
}

TEST(MediaClock, AHeldWallClockIsPausedUntilStarted) {
  WallClock c(2.0, 0.0, /*held=*/true);
  usleep(20000);
  ClockReading r = c.Read();
  EXPECT_TRUE(r.valid);
  EXPECT_TRUE(r.paused);
  EXPECT_EQ(r.media_s, 0.0);
  EXPECT_EQ(Extrapolate(r, SteadySeconds() + 0.5), 0.0);
  c.Start(SteadySeconds() - 0.25);
  r = c.Read();
  EXPECT_FALSE(r.paused);
  EXPECT_NEAR(r.media_s, 0.25, 0.05);
}

TEST(MediaClock, FakeClockCountsSeeksAndUpdates) {
  FakeClock c;
  EXPECT_FALSE(c.Read().valid);
  c.Update(1, 10);
  c.Seek(5, 11);
  const ClockReading r = c.Read();
  EXPECT_EQ(r.serial, 2u);
  EXPECT_EQ(r.seek_serial, 1u);
  EXPECT_DOUBLE_EQ(r.media_s, 5);
  c.SetEof(12);
  EXPECT_TRUE(c.Read().eof);
  c.Finish();
  EXPECT_TRUE(c.Read().finished);
}

}  // namespace
}  // namespace hapcine
