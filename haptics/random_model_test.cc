#include "haptics/random_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rotation.h"

namespace hapcine {
namespace {

double Peak(const std::vector<ActuatorFrame>& v) {
  double m = 0;
  for (const auto& f : v)
    for (const auto& a : f) m = std::max(m, a.cwiseAbs().maxCoeff());
  return m;
}

TEST(RandomModel, SeededScaledAndCentredAtTheEnds) {
  const SeatGeometry seat;
  RandomOptions o;
  const auto a = RandomFrames(20000, 1000, seat, o);
  const auto b = RandomFrames(20000, 1000, seat, o);
  o.seed = 2;
  const auto c = RandomFrames(20000, 1000, seat, o);
  EXPECT_EQ(a[12345][1], b[12345][1]);
  EXPECT_NE(a[12345][1], c[12345][1]);
  EXPECT_NEAR(Peak(a), seat.usable_half_m, 1e-12);
  for (int k = 0; k < kNumActuators; ++k) {
    EXPECT_EQ(a.front()[k], Eigen::Vector3d::Zero());
    EXPECT_EQ(a.back()[k], Eigen::Vector3d::Zero());
  }
}

TEST(RandomModel, ButterworthZeroPhaseResponse) {
  const double rate = 1000, fc = 0.5;
  auto gain_at = [&](double f) {
    std::vector<double> x(60000);
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * kPi * f * i / rate);
    const auto y = ButterworthLowPassZeroPhase(x, fc, rate);
    double num = 0, den = 0;  // middle 20 s, away from the edges
    for (size_t i = 20000; i < 40000; ++i) {
      num += y[i] * x[i];
      den += x[i] * x[i];
    }
    return num / den;  // in-phase gain (zero phase: the full gain)
  };
  EXPECT_NEAR(gain_at(0.05), 1.0, 0.01);
  // -3 dB at the stated cutoff, the combined response of both passes (it
  // was 1/2, -6 dB, when each pass was designed at the cutoff; -3 dB then
  // fell at 0.40 Hz).
  EXPECT_NEAR(gain_at(0.5), 1 / std::sqrt(2.0), 0.005);
  EXPECT_GT(gain_at(0.45), 1 / std::sqrt(2.0) + 0.02);
  EXPECT_LT(gain_at(0.55), 1 / std::sqrt(2.0) - 0.02);
  // 4th-order roll-off: 1 / (1 + (f / f0)^4), f0 = 1.25 fc.
  const double f0 = ZeroPhaseSectionCutoffHz(fc, rate);
  EXPECT_NEAR(f0 / fc, 1 / std::pow(std::sqrt(2.0) - 1, 0.25), 1e-4);
  EXPECT_NEAR(gain_at(5.0), 1 / (1 + std::pow(5.0 / f0, 4)), 2e-5);
}

TEST(RandomModel, MostPowerBelowTheCutoff) {
  const auto v = RandomFrames(30000, 1000, SeatGeometry(), RandomOptions());
  // Sample-to-sample steps are tiny for a 0.5 Hz signal: <= 2 pi f A / rate-ish.
  double max_step = 0;
  for (size_t i = 1; i < v.size(); ++i) {
    max_step = std::max(max_step, (v[i][0] - v[i - 1][0]).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(max_step, 0.045 * 2 * kPi * 2.0 / 1000);
}

TEST(RandomModel, OptionsCheck) {
  RandomOptions o;
  o.cutoff_hz = 0;
  EXPECT_ANY_THROW(o.Check());
  EXPECT_TRUE(RandomFrames(0, 1000, SeatGeometry(), RandomOptions()).empty());
}

}  // namespace
}  // namespace hapcine
