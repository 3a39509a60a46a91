#include "haptics/safety.h"

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <limits>
#include <random>

#include "core/error.h"

namespace hapcine {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Safety, OptionsRejectUnsafeSettings) {
  SafetyOptions o;
  EXPECT_NO_THROW(o.Check());
  o.max_force_n = 12;
  EXPECT_THROW(o.Check(), UsageError);
  o = SafetyOptions();
  o.workspace_half_m = 0.2;
  EXPECT_THROW(o.Check(), UsageError);
  o = SafetyOptions();
  o.watchdog_ramp_s = 0.05;
  EXPECT_THROW(o.Check(), UsageError);
  o = SafetyOptions();
  o.max_force_step_n = std::nan("");
  EXPECT_THROW(o.Check(), UsageError);
}

TEST(Safety, ForceLimitIsTheLowerOfOptionAndDevice) {
  SafetyOptions o;
  o.max_force_n = 9;
  EXPECT_DOUBLE_EQ(ActuatorSafety(o, 5).max_force_n(), 5);
  EXPECT_DOUBLE_EQ(ActuatorSafety(o, 20).max_force_n(), 9);
  EXPECT_DOUBLE_EQ(ActuatorSafety(o, std::nan("")).max_force_n(), 0);
}

TEST(Safety, NonFiniteForceGivesZeroAtOnceAndAFault) {
  ActuatorSafety s(SafetyOptions(), 9);
  for (int i = 0; i < 50; ++i) s.FilterForce(Eigen::Vector3d(0, 0, 5), 1);
  for (double bad : {std::nan(""), kInf, -kInf}) {
    const Eigen::Vector3d f = s.FilterForce(Eigen::Vector3d(bad, 1, 1), 1);
    EXPECT_EQ(f, Eigen::Vector3d::Zero());
    EXPECT_TRUE(s.tick_faults() & kFaultNonFiniteForce);
  }
  EXPECT_EQ(s.FilterForce(Eigen::Vector3d(1, 1, 1), std::nan("")), Eigen::Vector3d::Zero());
}

TEST(Safety, HugeForcesAreClampedWithoutOverflow) {
  ActuatorSafety s(SafetyOptions(), 9);
  Eigen::Vector3d f;
  for (int i = 0; i < 100; ++i) f = s.FilterForce(Eigen::Vector3d(1e300, -1e300, 1e300), 1);
  EXPECT_TRUE(f.allFinite());
  EXPECT_NEAR(f.norm(), 9, 1e-9);
  // Direction kept: equal magnitudes on each axis.
  EXPECT_NEAR(f.x(), -f.y(), 1e-9);
}

TEST(Safety, ForceChangePerTickIsRateLimited) {
  SafetyOptions o;
  o.max_force_step_n = 0.5;
  ActuatorSafety s(o, 9);
  Eigen::Vector3d prev = Eigen::Vector3d::Zero();
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d f = s.FilterForce(Eigen::Vector3d(i % 2 ? 8.0 : -8.0, 0, 0), 1);
    EXPECT_LE((f - prev).norm(), 0.5 + 1e-12);
    prev = f;
  }
}

TEST(Safety, TargetsAreClampedToTheCubeAndRateLimited) {
  SafetyOptions o;
  ActuatorSafety s(o, 9);
  Eigen::Vector3d t;
  for (int i = 0; i < 1000; ++i) t = s.FilterTarget(Eigen::Vector3d(1, -1, 1e300));
  EXPECT_TRUE(t.isApprox(Eigen::Vector3d(0.05, -0.05, 0.05)));
  EXPECT_TRUE(s.faults() & kFaultTargetClamped);
  // One step from there moves at most max_target_step_m.
  const Eigen::Vector3d next = s.FilterTarget(Eigen::Vector3d(-0.05, 0.05, -0.05));
  EXPECT_NEAR((next - t).norm(), o.max_target_step_m, 1e-12);
  // NaN target: hold.
  const Eigen::Vector3d held = s.FilterTarget(Eigen::Vector3d(std::nan(""), 0, 0));
  EXPECT_EQ(held, next);
  EXPECT_TRUE(s.tick_faults() & kFaultNonFiniteTarget);
}

TEST(Safety, WatchdogRampsToZeroWithin20MsAndRecovers) {
  SafetyOptions o;
  Watchdog w(o);
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(w.Update(0.001, true), 1.0);
  int ticks_to_zero = 0;
  while (w.Update(0.001, false) > 0) ++ticks_to_zero;
  EXPECT_LE(ticks_to_zero + 1, 20);  // zero at the 20th tick at the latest
  EXPECT_EQ(w.trips(), 1);
  // Healthy again: stays at zero for recover_after_s, then ramps up.
  for (int i = 0; i < 99; ++i) EXPECT_EQ(w.Update(0.001, true), 0.0);
  double g = 0;
  for (int i = 0; i < 200; ++i) g = w.Update(0.001, true);
  EXPECT_GT(g, 0.3);
  EXPECT_LT(g, 0.5);
  // A single long gap (100 ms) drops the gain at once.
  Watchdog w2(o);
  EXPECT_EQ(w2.Update(0.1, false), 0.0);
  EXPECT_EQ(w2.Update(std::nan(""), true), 0.0);
}

TEST(Safety, RandomAdversarialForcesNeverExceedTheLimit) {
  // Property: whatever comes in (random, huge, tiny, denormal, NaN, steps),
  // what comes out is finite and within the limit, and never jumps up by
  // more than the rate limit.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  const double specials[] = {0.0,  4.9e-324, -4.9e-324,    1e-310, 1e300, -1e300,
                             kInf, -kInf,    std::nan(""), 9.0,    -9.0,  1e6};
  for (double limit : {9.0, 3.0, 0.5}) {
    SafetyOptions o;
    o.max_force_n = limit;
    ActuatorSafety s(o, 9);
    Eigen::Vector3d prev = Eigen::Vector3d::Zero();
    for (int i = 0; i < 20000; ++i) {
      Eigen::Vector3d f;
      for (int k = 0; k < 3; ++k) {
        const int kind = static_cast<int>(rng() % 4);
        f[k] = kind == 0   ? specials[rng() % 12]
               : kind == 1 ? u(rng) * 1e3
               : kind == 2 ? u(rng) * 20
                           : u(rng) * 1e-300;
      }
      const double gain = (rng() % 10 == 0) ? specials[rng() % 12] : std::abs(u(rng));
      const Eigen::Vector3d out = s.FilterForce(f, gain);
      ASSERT_TRUE(out.allFinite()) << i;
      ASSERT_LE(out.norm(), limit + 1e-12) << i;
      if (out.norm() > prev.norm()) {
        ASSERT_LE(out.norm() - prev.norm(), o.max_force_step_n + 1e-9) << i;
      }
      prev = out;
    }
  }
}

class RecordingDevice : public Device {
 public:
  void Open() override { open = true; }
  void Close() noexcept override { open = false; }
  DeviceState Exchange(const Eigen::Vector3d& f) override {
    last = f;
    ++exchanges;
    return DeviceState();
  }
  double MaxForceN() const override { return 9; }
  std::string Name() const override { return "recording"; }
  double LastSentForceN() const override { return last.norm(); }
  bool open = false;
  int exchanges = 0;
  Eigen::Vector3d last = Eigen::Vector3d::Ones();
};

TEST(Safety, GuardZeroesAndClosesOnException) {
  HapSeat seat;
  seat.devices[0] = std::make_unique<RecordingDevice>();
  seat.devices[2] = std::make_unique<RecordingDevice>();
  auto* d0 = static_cast<RecordingDevice*>(seat.devices[0].get());
  d0->Open();
  d0->last = Eigen::Vector3d(5, 5, 5);
  try {
    ZeroForceGuard guard(seat);
    throw std::runtime_error("boom");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(d0->last, Eigen::Vector3d::Zero());
  EXPECT_FALSE(d0->open);
  EXPECT_GE(d0->exchanges, 1);
}

}  // namespace
}  // namespace hapcine
