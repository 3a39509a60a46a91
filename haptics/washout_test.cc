#include "haptics/washout.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

std::vector<double> Times(size_t n, double rate) {
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i) t[i] = i / rate;
  return t;
}

TEST(Washout, FirstOrderHighPassDecaysAHeldOffsetWithTau) {
  const auto t = Times(10001, 1000);  // 10 s
  std::vector<double> x(t.size());
  for (size_t i = 0; i < x.size(); ++i) x[i] = t[i] >= 1.0 ? 1.0 : 0.0;  // step at 1 s
  HighPassInPlace(t, &x, 2.0, 1);
  EXPECT_NEAR(x[1000], 1.0, 1e-3);             // the onset passes
  EXPECT_NEAR(x[3000], std::exp(-1.0), 2e-3);  // one tau later
  EXPECT_NEAR(x[9000], std::exp(-4.0), 2e-3);
}

TEST(Washout, SecondOrderHighPassRemovesAConstantVelocityDrift) {
  const auto t = Times(60001, 1000);  // 60 s of constant velocity
  std::vector<double> x1(t.size()), x2;
  for (size_t i = 0; i < t.size(); ++i) x1[i] = 0.1 * t[i];
  x2 = x1;
  HighPassInPlace(t, &x1, 3.0, 1);
  HighPassInPlace(t, &x2, 3.0, 2);
  EXPECT_NEAR(x1.back(), 0.1 * 3.0, 1e-3);  // order 1: plateau v * tau
  EXPECT_LT(std::abs(x2.back()), 1e-5);     // order 2: back to centre
}

TEST(Washout, HighPassHandlesIrregularSampling) {
  std::vector<double> t = {0, 0.03, 0.07, 0.1, 0.2, 0.21}, x(6, 1.0);
  HighPassInPlace(t, &x, 1.0, 2);
  for (double v : x) EXPECT_EQ(v, 0.0);  // a constant is all "sustained offset"
}

TEST(Washout, SmootherStepIsC2AndClamped) {
  EXPECT_EQ(SmootherStep(-1), 0);
  EXPECT_EQ(SmootherStep(2), 1);
  EXPECT_DOUBLE_EQ(SmootherStep(0.5), 0.5);
  const double h = 1e-4;
  EXPECT_NEAR((SmootherStep(h) - SmootherStep(0)) / h, 0, 1e-6);
  EXPECT_NEAR((SmootherStep(1) - SmootherStep(1 - h)) / h, 0, 1e-6);
}

TEST(Washout, CutCrossfadeNeverJumpsAndStaysInTheBox) {
  const auto t = Times(2001, 1000);
  std::vector<ActuatorFrame> v(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    for (auto& a : v[i]) a = Eigen::Vector3d::Constant(t[i] < 1.0 ? 0.045 : -0.045);
  }
  ApplyCutTransitions(t, {1.0}, 0.5, &v);
  double max_step = 0;
  for (size_t i = 1; i < v.size(); ++i) {
    max_step = std::max(max_step, std::abs(v[i][0].x() - v[i - 1][0].x()));
    EXPECT_LE(std::abs(v[i][0].x()), 0.045 + 1e-12);
  }
  // Smootherstep peak slope 1.875 / ramp over a 0.09 m swing at 1 kHz.
  EXPECT_LE(max_step, 1.875 * 0.09 / 0.5 / 1000 + 1e-9);
  EXPECT_NEAR(v[1500][0].x(), -0.045, 1e-12);  // finished after the ramp
}

TEST(Washout, VelocityLimitBoundsEveryStep) {
  std::vector<ActuatorFrame> v(100);
  for (size_t i = 0; i < v.size(); ++i) {
    for (auto& a : v[i]) a = Eigen::Vector3d::Constant(i < 50 ? 0.0 : 0.04);
  }
  EXPECT_GT(LimitVelocity(0.001, &v), 0);
  for (size_t i = 1; i < v.size(); ++i) {
    EXPECT_LE((v[i][2] - v[i - 1][2]).cwiseAbs().maxCoeff(), 0.001 + 1e-15);
  }
  EXPECT_NEAR(v.back()[1].y(), 0.04, 1e-12);  // reaches the target eventually
}

TEST(Washout, SpeedLimitOnUnevenRowsScalesTheStepWithTheirSpacing) {
  // 100 Hz rows with 1 kHz rows between 0.10 and 0.12 s; a step to 0.04 m at 0.105 s.
  std::vector<HapticSample> s;
  for (int ms = 0; ms <= 300; ms += (ms >= 100 && ms < 120) ? 1 : 10) {
    HapticSample x;
    x.time_s = ms / 1000.0;
    for (auto& a : x.pos_m) a = Eigen::Vector3d::Constant(ms < 105 ? 0.0 : 0.04);
    s.push_back(x);
  }
  std::vector<char> limited;
  EXPECT_GT(LimitSpeed(0.5, 100, &s, &limited), 0);
  EXPECT_EQ(limited.size(), s.size());
  for (size_t i = 1; i < s.size(); ++i) {
    const double dt = s[i].time_s - s[i - 1].time_s;
    EXPECT_LE((s[i].pos_m[1] - s[i - 1].pos_m[1]).cwiseAbs().maxCoeff(), 0.5 * dt + 1e-12) << i;
    // Limited from the step until the ramp reaches 0.04 m (8 mm at 0.12 s,
    // then 5 mm per 10 ms row: 38 mm at 0.18 s).
    EXPECT_EQ(limited[i] != 0, s[i].time_s > 0.1045 && s[i].time_s < 0.1805)
        << i;
  }
  // The ramp starts at the first 1 kHz row after the step, as at 1 kHz:
  // 0.5 mm per millisecond from 0.105 s.
  EXPECT_NEAR(s[15].time_s, 0.105, 1e-12);
  EXPECT_NEAR(s[15].pos_m[0].x(), 0.0005, 1e-12);
  EXPECT_NEAR(s[30].pos_m[0].x(), 0.008, 1e-12);  // 0.12 s
  // Even rows take LimitVelocity's very step.
  std::vector<HapticSample> even;
  for (int i = 0; i <= 20; ++i) {
    HapticSample x;
    x.time_s = i / 100.0;
    x.pos_m[2].x() = i < 10 ? 0.0 : 0.04;
    even.push_back(x);
  }
  std::vector<HapticSample> copy = even;
  EXPECT_EQ(LimitSpeed(0.5, 100, &even), LimitVelocity(0.5 / 100, &copy));
  for (size_t i = 0; i < even.size(); ++i) EXPECT_EQ(even[i].pos_m[2].x(), copy[i].pos_m[2].x());
}

TEST(Washout, ClampCatchesOutliersAndNaN) {
  std::vector<ActuatorFrame> v(3);
  for (auto& f : v)
    for (auto& a : f) a.setZero();
  v[1][2].x() = 0.3;
  v[2][0].z() = std::nan("");
  EXPECT_EQ(ClampToWorkspace(0.048, &v), 2);
  EXPECT_DOUBLE_EQ(v[1][2].x(), 0.048);
  EXPECT_EQ(v[2][0].z(), 0.0);
}

TEST(Washout, OptionsCheck) {
  WashoutOptions o;
  EXPECT_NO_THROW(o.Check());
  o.order = 3;
  EXPECT_ANY_THROW(o.Check());
  o = WashoutOptions();
  o.tau_s = 0;
  EXPECT_ANY_THROW(o.Check());
}

}  // namespace
}  // namespace hapcine
