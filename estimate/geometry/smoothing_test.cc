#include "estimate/geometry/smoothing.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace hapcine {
namespace {

TEST(Smoothing, RampPassesThroughWithoutLag) {
  std::vector<double> x;
  for (int i = 0; i < 50; ++i) x.push_back(0.3 * i);
  const auto y = SmoothScalars(x, 3);
  for (int i = 0; i < 50; ++i) EXPECT_NEAR(y[i], x[i], 1e-9) << i;
}

TEST(Smoothing, StepIsNotDelayed) {
  std::vector<double> x(60, 0.0);
  for (int i = 30; i < 60; ++i) x[i] = 1;
  const auto y = SmoothScalars(x, 2);
  // Zero phase: the half-way point stays between samples 29 and 30, and the
  // response is antisymmetric about it.
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(y[29 - k] + y[30 + k], 1.0, 1e-12) << k;
  EXPECT_LT(y[29], 0.5);
  EXPECT_GT(y[30], 0.5);
  EXPECT_EQ(y[0], 0);
  EXPECT_EQ(y[59], 1);
}

TEST(Smoothing, ReducesJitterOnRotations) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0, 0.002);
  std::vector<Eigen::Quaterniond> truth, noisy;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitY()));
    truth.push_back(q);
    noisy.push_back(q * ExpRotation(Eigen::Vector3d(g(rng), g(rng), g(rng))));
  }
  const auto smooth = SmoothRotations(noisy, 2);
  double e_noisy = 0, e_smooth = 0;
  for (int i = 5; i < 95; ++i) {
    e_noisy += truth[i].angularDistance(noisy[i]);
    e_smooth += truth[i].angularDistance(smooth[i]);
  }
  EXPECT_LT(e_smooth, 0.6 * e_noisy);
  // A constant-rate rotation is reproduced exactly (no lag).
  const auto clean = SmoothRotations(truth, 2);
  for (int i = 0; i < 100; ++i) EXPECT_LT(truth[i].angularDistance(clean[i]), 1e-9);
}

TEST(Smoothing, ConstantZeroStaysExactlyZero) {
  std::vector<Eigen::Vector3d> c(20, Eigen::Vector3d::Zero());
  for (const auto& v : SmoothVectors(c, 2)) EXPECT_EQ(v, Eigen::Vector3d::Zero());
}

TEST(Smoothing, LogExpRoundTrip) {
  const Eigen::Vector3d w(0.3, -0.2, 0.1);
  EXPECT_LT((LogRotation(ExpRotation(w)) - w).norm(), 1e-12);
  EXPECT_EQ(LogRotation(Eigen::Quaterniond::Identity()), Eigen::Vector3d::Zero());
}

// A sigma past any int's range (--smooth-sigma 1e10) reaches the path's ends:
// a window as wide as the edges allow, and a ramp still passes through.
TEST(Smoothing, HugeSigmaIsBoundedByThePathEnds) {
  std::vector<double> x;
  for (int i = 0; i < 30; ++i) x.push_back(0.5 * i);
  for (const double sigma : {7e8, 1e10, 1e300, std::numeric_limits<double>::infinity()}) {
    const auto y = SmoothScalars(x, sigma);
    ASSERT_EQ(y.size(), x.size());
    for (int i = 0; i < 30; ++i) EXPECT_NEAR(y[i], x[i], 1e-9) << sigma << " " << i;
    const auto q = SmoothRotations(std::vector<Eigen::Quaterniond>(5, Eigen::Quaterniond::Identity()), sigma);
    for (const auto& v : q) EXPECT_LT(v.angularDistance(Eigen::Quaterniond::Identity()), 1e-12);
  }
}

// A sigma whose square underflows is no smoothing, not 0/0.
TEST(Smoothing, TinySigmaLeavesThePathAlone) {
  const std::vector<double> x = {0, 3, -1, 2, 5};
  EXPECT_EQ(SmoothScalars(x, 1e-300), x);
}

}  // namespace
}  // namespace hapcine
