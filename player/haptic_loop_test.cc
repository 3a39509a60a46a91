#include "player/haptic_loop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <sstream>

#include "haptics/safety.h"
#include "haptics/sim_device.h"

namespace hapcine {
namespace {

constexpr double kDt = 0.001;

HapticTrack MakeTrack(double duration_s, double rate_hz,
                      const std::function<void(double, Eigen::Vector3d*)>& fn) {
  HapticTrack t;
  t.rate_hz = rate_hz;
  t.model = "test";
  t.source = "test";
  const int n = static_cast<int>(std::round(duration_s * rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    HapticSample s;
    s.time_s = i / rate_hz;
    fn(s.time_s, s.pos_m);
    t.samples.push_back(s);
  }
  return t;
}

HapSeat SimSeat(SimDeviceOptions o = SimDeviceOptions()) {
  HapSeat seat;
  for (auto& d : seat.devices) {
    d = std::make_unique<SimDevice>(o);
    d->Open();
  }
  return seat;
}

SimDevice& Sim(HapSeat& seat, int a) { return static_cast<SimDevice&>(*seat.devices[a]); }

// Steps the loop like mpv would drive it: the clock publishes every 40 ms
// (25 fps), the loop ticks every 1 ms. Returns false if the loop stopped.
struct Driver {
  FakeClock clock;
  double wall = 100.0;  // arbitrary epoch: nothing may assume 0
  double media = 0;
  bool paused = false;
  bool updating = true;
  double film_end_s = 1e9;  // the clock reports eof from here on
  int tick = 0;
  bool Step(HapticLoop& loop) {
    if (updating && tick % 40 == 0) clock.Update(media, wall, paused);
    if (media >= film_end_s && !clock.Read().eof) clock.SetEof(wall);
    const bool go = loop.Tick(wall);
    wall += kDt;
    if (!paused) media += kDt;
    ++tick;
    return go;
  }
};

// A 100 Hz monotone cubic track: the loop's targets follow the 1 kHz track of
// the same motion within 0.1 mm, and a jump to the clamp edge is never
// overshot (the interpolation stays between rows, then the safety filters).
TEST(HapticLoop, AHundredHertzCubicTrackPlaysLikeTheKilohertzOne) {
  ClearStopRequest();
  auto motion = [](double t, Eigen::Vector3d* p) {
    p[0] = Eigen::Vector3d(0.03 * std::sin(2 * M_PI * 0.7 * t), 0, 0);
    p[1] = Eigen::Vector3d(0, t < 3 ? -0.01 : 0.048, 0);  // a jump to the clamp edge at 3 s
    p[2] = Eigen::Vector3d(0, 0, 0.01 * std::cos(2 * M_PI * 0.3 * t));
  };
  const HapticTrack fine = MakeTrack(6, 1000, motion);
  HapticTrack stored = MakeTrack(6, 100, motion);
  stored.interpolation = TrackInterpolation::kMonotoneCubic;
  HapSeat seat_fine = SimSeat(), seat_stored = SimSeat();
  Driver drv_fine, drv_stored;
  drv_fine.film_end_s = drv_stored.film_end_s = 6;
  HapticLoop loop_fine(fine, seat_fine, drv_fine.clock, LoopOptions());
  HapticLoop loop_stored(stored, seat_stored, drv_stored.clock, LoopOptions());
  double worst_smooth = 0, highest_left_y = -1;
  while (drv_fine.Step(loop_fine) && drv_stored.Step(loop_stored)) {
    const double t = drv_fine.media;
    if (t < 1.5 || t > 5.9) continue;  // start ramp, end ramp
    worst_smooth = std::max(worst_smooth, (loop_fine.last_target_m(0) - loop_stored.last_target_m(0)).norm());
    worst_smooth = std::max(worst_smooth, (loop_fine.last_target_m(2) - loop_stored.last_target_m(2)).norm());
    highest_left_y = std::max(highest_left_y, loop_stored.last_target_m(1).y());
  }
  EXPECT_LT(worst_smooth, 0.1e-3);
  EXPECT_LE(highest_left_y, 0.048);
  EXPECT_GT(highest_left_y, 0.047);  // it did get there
}

TEST(HapticLoop, HeadlessPlayOnTheSimFollowsTheTrack) {
  ClearStopRequest();
  const HapticTrack track = MakeTrack(8, 100, [](double t, Eigen::Vector3d* p) {
    p[0] = Eigen::Vector3d(0.02 * std::sin(2 * M_PI * 0.5 * t), 0, 0);
    p[1] = Eigen::Vector3d(0, 0.01, 0);
    p[2] = Eigen::Vector3d(0, 0, -0.02 + 0.005 * t);
  });
  HapSeat seat = SimSeat();
  Driver drv;
  drv.film_end_s = 8;
  drv.clock.SetTruth(-100.0, 1.0);  // true media = wall - 100
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  double sq = 0, worst = 0;
  int n = 0;
  while (drv.Step(loop)) {
    if (drv.media < 2.0 || drv.media > 7.9) continue;  // start ramp + settling
    Eigen::Vector3d want[3];
    track.Sample(drv.media, want);
    for (int a = 0; a < 3; ++a) {
      const double e = (Sim(seat, a).true_pos_m() - want[a]).norm();
      sq += e * e;
      worst = std::max(worst, e);
      ++n;
    }
  }
  const double rms = std::sqrt(sq / n);
  std::printf("sim tracking: rms %.2f mm, max %.2f mm over %d samples\n", rms * 1e3, worst * 1e3,
              n);
  EXPECT_LT(rms, 0.002);
  EXPECT_LT(worst, 0.004);
  EXPECT_EQ(loop.status(), LoopStatus::kFinished);
  // The end of the film returned everything to the centre.
  for (int a = 0; a < 3; ++a) EXPECT_LT(loop.last_target_m(a).norm(), 1e-9);
  // Sync: the loop extrapolates between 25 Hz updates exactly (error 0 up to rounding).
  EXPECT_LT(loop.stats().sync_error.max_s(), 2e-6);
  EXPECT_EQ(loop.stats().missed_ticks, 0);
}

TEST(HapticLoop, ATrackShorterThanTheFilmHoldsTheCentreUntilTheFilmEnds) {
  ClearStopRequest();
  const HapticTrack track = MakeTrack(1, 100, [](double, Eigen::Vector3d* p) {
    for (int a = 0; a < 3; ++a) p[a] = Eigen::Vector3d(0.01, 0, 0);
  });
  HapSeat seat = SimSeat();
  Driver drv;
  drv.film_end_s = 3;
  LoopOptions o;
  o.start_ramp_s = 0.1;
  o.end_ramp_s = 0.2;
  HapticLoop loop(track, seat, drv.clock, o);
  int i = 0;
  for (; i < 10000 && drv.Step(loop); ++i) {
    if (drv.media > 0.5 && drv.media < 0.9) {
      EXPECT_NEAR(loop.last_target_m(0).x(), 0.01, 1e-9);
    }
    if (drv.media > 1.3 && drv.media < 3.0) {
      EXPECT_LT(loop.last_target_m(0).norm(), 1e-9);
    }
  }
  EXPECT_EQ(loop.status(), LoopStatus::kFinished);
  EXPECT_GE(drv.media, 3.0) << "stopped before the film ended";
  EXPECT_LT(drv.media, 3.5);
  EXPECT_EQ(Sim(seat, 0).last_force_n().norm(), 0.0);
}

TEST(HapticLoop, PauseHoldsThePosition) {
  ClearStopRequest();
  const HapticTrack track = MakeTrack(
      10, 100, [](double t, Eigen::Vector3d* p) { p[0] = Eigen::Vector3d(0.003 * t, 0, 0); });
  HapSeat seat = SimSeat();
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(drv.Step(loop));
  drv.paused = true;
  drv.Step(loop);
  const Eigen::Vector3d held = loop.last_target_m(0);
  for (int i = 0; i < 3000; ++i) ASSERT_TRUE(drv.Step(loop));  // 3 s paused, no stall trip
  EXPECT_LT((loop.last_target_m(0) - held).norm(), 1e-12);
  EXPECT_NEAR(Sim(seat, 0).true_pos_m().x(), held.x() * 300 / 310, 5e-4);
  EXPECT_EQ(loop.stats().watchdog_trips, 0);
  EXPECT_DOUBLE_EQ(loop.gain(), 1.0);
}

TEST(HapticLoop, SeekRampsSmoothlyToTheNewTarget) {
  ClearStopRequest();
  // A step in the track at 3 s: 0 before, 4 cm after.
  const HapticTrack track = MakeTrack(10, 100, [](double t, Eigen::Vector3d* p) {
    p[0] = Eigen::Vector3d(t < 3 ? 0 : 0.04, 0, 0);
  });
  HapSeat seat = SimSeat();
  Driver drv;
  LoopOptions o;
  HapticLoop loop(track, seat, drv.clock, o);
  for (int i = 0; i < 1500; ++i) ASSERT_TRUE(drv.Step(loop));
  // Seek to 6 s.
  drv.media = 6.0;
  drv.clock.Seek(drv.media, drv.wall);
  double prev = loop.last_target_m(0).x(), max_step = 0;
  std::vector<double> x;
  for (int i = 0; i < 500; ++i) {
    ASSERT_TRUE(drv.Step(loop));
    x.push_back(loop.last_target_m(0).x());
    max_step = std::max(max_step, std::abs(x.back() - prev));
    prev = x.back();
  }
  EXPECT_EQ(loop.stats().seeks, 1);
  // Cosine ramp over 0.3 s: half-way at 150 ms, done by 300 ms, and never
  // a jump larger than the ramp's peak speed (pi/2 * 4 cm / 0.3 s per ms).
  EXPECT_NEAR(x[149], 0.02, 0.002);
  EXPECT_NEAR(x[300], 0.04, 1e-9);
  EXPECT_LT(max_step, M_PI / 2 * 0.04 / 300 * 1.05);
}

TEST(HapticLoop, WatchdogZeroesForceWithin20msOfAClockStall) {
  ClearStopRequest();
  const HapticTrack track =
      MakeTrack(10, 100, [](double t, Eigen::Vector3d* p) { p[1] = Eigen::Vector3d(0, 0.03, 0); });
  SimDeviceOptions so;
  so.hand_stiffness_n_m = 200;  // a firm hand keeps a steady force on the grip
  HapSeat seat = SimSeat(so);
  Driver drv;
  LoopOptions o;
  HapticLoop loop(track, seat, drv.clock, o);
  for (int i = 0; i < 3000; ++i) ASSERT_TRUE(drv.Step(loop));
  EXPECT_GT(loop.last_force_n(1).norm(), 1.0);
  // The player freezes: no more clock updates while "playing".
  drv.updating = false;
  const double last_update = drv.wall - kDt * (drv.tick % 40 == 0 ? 40 : drv.tick % 40);
  double detected = -1, zero_at = -1;
  for (int i = 0; i < 600; ++i) {
    ASSERT_TRUE(drv.Step(loop));
    const double now = drv.wall - kDt;
    if (detected < 0 && loop.gain() < 1) detected = now;
    if (detected >= 0 && zero_at < 0 && loop.last_force_n(1).norm() == 0) zero_at = now;
  }
  ASSERT_GT(detected, 0);
  ASSERT_GT(zero_at, 0);
  EXPECT_NEAR(detected - last_update, o.safety.clock_stall_s, 0.0025);
  EXPECT_LE(zero_at - detected, 0.020 + 1e-9);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(loop.last_force_n(a).norm(), 0.0);
  EXPECT_EQ(loop.stats().watchdog_trips, 1);
}

TEST(HapticLoop, MissedDeadlinesTripTheWatchdogAndAreCounted) {
  ClearStopRequest();
  const HapticTrack track =
      MakeTrack(10, 100, [](double, Eigen::Vector3d* p) { p[0] = Eigen::Vector3d(0.02, 0, 0); });
  HapSeat seat = SimSeat();
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(drv.Step(loop));
  drv.wall += 0.0096;  // the thread was descheduled for ~10 ms
  drv.media += 0.0096;
  ASSERT_TRUE(drv.Step(loop));
  EXPECT_EQ(loop.stats().missed_ticks, 10);
  EXPECT_EQ(loop.stats().watchdog_trips, 1);
  EXPECT_LT(loop.gain(), 1.0);
}

class ThrowingDevice : public SimDevice {
 public:
  int throw_at = -1, count = 0;
  DeviceState Exchange(const Eigen::Vector3d& f) override {
    if (++count == throw_at) throw std::runtime_error("driver bug");
    return SimDevice::Exchange(f);
  }
};

TEST(HapticLoop, AnExceptionInTheTickZeroesEveryDeviceAndPropagates) {
  ClearStopRequest();
  const HapticTrack track = MakeTrack(10, 100, [](double, Eigen::Vector3d* p) {
    for (int a = 0; a < 3; ++a) p[a] = Eigen::Vector3d(0.02, 0.02, 0);
  });
  SimDeviceOptions so;
  so.hand_stiffness_n_m = 200;
  HapSeat seat = SimSeat(so);
  auto thrower = std::make_unique<ThrowingDevice>();
  thrower->Open();
  thrower->throw_at = 2500;
  ThrowingDevice* t = thrower.get();
  seat.devices[1] = std::move(thrower);
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  bool thrown = false;
  try {
    while (drv.Step(loop)) {
    }
  } catch (const std::runtime_error&) {
    thrown = true;
  }
  ASSERT_TRUE(thrown);
  EXPECT_EQ(loop.status(), LoopStatus::kFaulted);
  EXPECT_EQ(Sim(seat, 0).last_force_n(), Eigen::Vector3d::Zero());
  EXPECT_EQ(Sim(seat, 2).last_force_n(), Eigen::Vector3d::Zero());
  EXPECT_EQ(t->last_force_n(), Eigen::Vector3d::Zero());  // ZeroAll reached it too
  EXPECT_FALSE(loop.Tick(drv.wall));                      // stays stopped
}

class FaultingDevice : public SimDevice {
 public:
  int fault_at = -1, count = 0;
  DeviceState Exchange(const Eigen::Vector3d& f) override {
    DeviceState s = SimDevice::Exchange(f);
    if (++count >= fault_at) s.fault = DeviceFault::kTransferError;
    return s;
  }
};

TEST(HapticLoop, AnUnpluggedDeviceStopsTheLoopWithZeroForceAndAFaultLog) {
  ClearStopRequest();
  const HapticTrack track =
      MakeTrack(10, 100, [](double, Eigen::Vector3d* p) { p[0] = Eigen::Vector3d(0.02, 0, 0); });
  HapSeat seat = SimSeat();
  auto f = std::make_unique<FaultingDevice>();
  f->Open();
  f->fault_at = 1200;
  seat.devices[2] = std::move(f);
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  while (drv.Step(loop)) {
  }
  EXPECT_EQ(loop.status(), LoopStatus::kFaulted);
  EXPECT_NE(loop.fault_message().find("unplugged"), std::string::npos);
  EXPECT_EQ(Sim(seat, 0).last_force_n(), Eigen::Vector3d::Zero());
  std::ostringstream dump;
  loop.DumpRecent(dump);
  int lines = 0;
  for (char c : dump.str()) lines += c == '\n';
  EXPECT_EQ(lines, 1 + 1200);  // header + every tick so far (ring not yet full)
}

TEST(HapticLoop, StopRequestZeroesAndStops) {
  ClearStopRequest();
  const HapticTrack track =
      MakeTrack(10, 100, [](double, Eigen::Vector3d* p) { p[0] = Eigen::Vector3d(0.02, 0, 0); });
  HapSeat seat = SimSeat();
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  for (int i = 0; i < 1500; ++i) ASSERT_TRUE(drv.Step(loop));
  EXPECT_GT(Sim(seat, 0).last_force_n().norm(), 0);
  RequestStop();  // what SIGINT/SIGTERM do
  EXPECT_FALSE(drv.Step(loop));
  ClearStopRequest();
  EXPECT_EQ(loop.status(), LoopStatus::kStopped);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(Sim(seat, a).last_force_n(), Eigen::Vector3d::Zero());
}

TEST(HapticLoop, NoPositionForceBeforeHoming) {
  ClearStopRequest();
  const HapticTrack track =
      MakeTrack(10, 100, [](double, Eigen::Vector3d* p) { p[0] = Eigen::Vector3d(0.04, 0, 0); });
  SimDeviceOptions so;
  so.homed_after_exchanges = 500;
  so.hand_stiffness_n_m = 0;  // the grip stays where the user left it
  so.start_pos_m = Eigen::Vector3d(-0.02, 0, 0);
  HapSeat seat = SimSeat(so);
  Driver drv;
  HapticLoop loop(track, seat, drv.clock, LoopOptions());
  for (int i = 0; i < 499; ++i) {
    ASSERT_TRUE(drv.Step(loop));
    ASSERT_EQ(Sim(seat, 0).last_force_n(), Eigen::Vector3d::Zero()) << i;
    ASSERT_FALSE(loop.all_homed()) << i;
  }
  // After homing the start ramp begins where the grip is.
  for (int i = 0; i < 3; ++i) drv.Step(loop);
  EXPECT_TRUE(loop.all_homed());
  EXPECT_NEAR(loop.last_target_m(0).x(), -0.02, 1e-3);
}

// Records every force a device is commanded and checks it.
class CheckedDevice : public SimDevice {
 public:
  explicit CheckedDevice(double limit) : limit_(limit) {}
  DeviceState Exchange(const Eigen::Vector3d& f) override {
    ++count;
    if (!f.allFinite()) ++non_finite;
    if (f.norm() > limit_ + 1e-12) ++over;
    max_seen = std::max(max_seen, f.norm());
    return SimDevice::Exchange(f);
  }
  int64_t count = 0, non_finite = 0, over = 0;
  double max_seen = 0;

 private:
  double limit_;
};

TEST(HapticLoop, AdversarialTracksNeverProduceUnsafeForces) {
  ClearStopRequest();
  const double inf = std::numeric_limits<double>::infinity();
  const double specials[] = {1e300,   -1e300, inf,  -inf, std::nan(""), 4.9e-324,
                             -1e-310, 0.5,    -0.5, 1e6,  0.05,         -0.05};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<std::function<double(double)>> gens = {
      [&](double) { return specials[rng() % 12]; },                       // garbage
      [&](double t) { return std::fmod(t, 0.5) < 0.25 ? 0.05 : -0.05; },  // full-scale steps
      [&](double) { return u(rng) * 10; },                                // random, out of range
      [&](double t) { return 1e300 * std::sin(t); },                      // huge
      [&](double t) { return 4.9e-324 * t; },                             // denormals
  };
  for (double limit : {9.0, 2.0}) {
    for (size_t g = 0; g < gens.size(); ++g) {
      HapticTrack track;
      track.rate_hz = 200;
      for (int i = 0; i <= 600; ++i) {
        HapticSample s;
        s.time_s = i / 200.0;
        for (int a = 0; a < 3; ++a)
          for (int k = 0; k < 3; ++k) s.pos_m[a][k] = gens[g](s.time_s + 0.01 * (3 * a + k));
        track.samples.push_back(s);
      }
      HapSeat seat;
      std::vector<CheckedDevice*> checked;
      for (auto& d : seat.devices) {
        auto c = std::make_unique<CheckedDevice>(limit);
        c->Open();
        checked.push_back(c.get());
        d = std::move(c);
      }
      Driver drv;
      LoopOptions o;
      o.safety.max_force_n = limit;
      o.k_n_m = 1000;  // stiff, to provoke large forces
      HapticLoop loop(track, seat, drv.clock, o);
      // A clock that also misbehaves: seeks, pauses and jumps.
      for (int i = 0; i < 4000 && drv.Step(loop); ++i) {
        if (i % 700 == 0) {
          drv.media = u(rng) * 4 + 1;
          drv.clock.Seek(drv.media, drv.wall);
        }
        if (i % 900 == 0) drv.paused = !drv.paused;
      }
      for (CheckedDevice* c : checked) {
        EXPECT_GT(c->count, 100);
        EXPECT_EQ(c->non_finite, 0) << "generator " << g;
        EXPECT_EQ(c->over, 0) << "generator " << g << " limit " << limit << " max " << c->max_seen;
        EXPECT_TRUE(c->true_pos_m().allFinite());
      }
    }
  }
}

TEST(HapticLoop, OptionsAreChecked) {
  LoopOptions o;
  o.k_n_m = -1;
  EXPECT_THROW(o.Check(), std::exception);
  o = LoopOptions();
  o.d_n_s_m = std::nan("");
  EXPECT_THROW(o.Check(), std::exception);
  o = LoopOptions();
  o.safety.max_force_n = 50;
  EXPECT_THROW(o.Check(), std::exception);
}

}  // namespace
}  // namespace hapcine
