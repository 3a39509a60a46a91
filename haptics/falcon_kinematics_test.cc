#include "haptics/falcon_kinematics.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace hapcine {
namespace {

// The notes' reachable cube: x, y in [-0.03, 0.03], z in [0.095, 0.155].
std::vector<Eigen::Vector3d> WorkspaceGrid(int n = 7) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        pts.emplace_back(-0.03 + 0.06 * i / (n - 1), -0.03 + 0.06 * j / (n - 1),
                         0.095 + 0.06 * k / (n - 1));
  return pts;
}

TEST(FalconKinematics, InverseThenForwardRoundTripsOverTheWorkspace) {
  FalconKinematics kin;
  double worst = 0;
  for (const Eigen::Vector3d& p : WorkspaceGrid()) {
    Eigen::Vector3d theta;
    ASSERT_TRUE(kin.Inverse(p, &theta)) << p.transpose();
    // Cold start at the centre, as after power-up.
    Eigen::Vector3d q;
    ASSERT_TRUE(kin.Forward(theta, FalconCentre(), &q)) << p.transpose();
    worst = std::max(worst, (q - p).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(FalconKinematics, WarmStartConvergesInFewIterations) {
  FalconKinematics kin;
  const Eigen::Vector3d p(0.01, -0.02, 0.13);
  Eigen::Vector3d theta, q;
  ASSERT_TRUE(kin.Inverse(p, &theta));
  // 1 mm away, as between two ticks at high speed: 3 iterations suffice.
  EXPECT_TRUE(kin.Forward(theta, p + Eigen::Vector3d(0.001, 0, 0), &q, 3));
  EXPECT_LT((q - p).norm(), 1e-9);
}

TEST(FalconKinematics, AnglesAtTheCentreArePlausibleEncoderCounts) {
  FalconKinematics kin;
  Eigen::Vector3d theta;
  ASSERT_TRUE(kin.Inverse(FalconCentre(), &theta));
  // Symmetric legs: equal angles at the centre line.
  EXPECT_NEAR(theta[0], theta[1], 1e-9);
  EXPECT_NEAR(theta[1], theta[2], 1e-9);
  const double counts = AngleRadToEncoder(theta[0]);
  EXPECT_LT(std::abs(counts), 32767.0);
  EXPECT_NEAR(EncoderToAngleRad(static_cast<int16_t>(std::lround(counts))), theta[0],
              0.5 * kFalconDegPerCount * M_PI / 180 + 1e-12);
}

TEST(FalconKinematics, JacobianMatchesCentralDifferences) {
  FalconKinematics kin;
  const double h = 1e-7;
  for (const Eigen::Vector3d& p : WorkspaceGrid(4)) {
    Eigen::Matrix3d analytic;
    ASSERT_TRUE(kin.AngleJacobian(p, &analytic));
    Eigen::Matrix3d numeric;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d tp, tm;
      ASSERT_TRUE(kin.Inverse(p + h * Eigen::Vector3d::Unit(c), &tp));
      ASSERT_TRUE(kin.Inverse(p - h * Eigen::Vector3d::Unit(c), &tm));
      numeric.col(c) = (tp - tm) / (2 * h);
    }
    EXPECT_LT((analytic - numeric).norm(), 1e-5 * numeric.norm()) << "at " << p.transpose() << "\n"
                                                                  << analytic << "\nvs\n"
                                                                  << numeric;
  }
}

TEST(FalconKinematics, TorqueDoesTheSameVirtualWorkAsTheForce) {
  // tau . dtheta == F . dp for a small displacement: the definition of J^T F.
  FalconKinematics kin;
  const Eigen::Vector3d p(0.012, 0.005, 0.12), force(3.0, -2.0, 5.0), dp(1e-6, -2e-6, 1.5e-6);
  Eigen::Vector3d tau, t0, t1;
  ASSERT_TRUE(kin.ForceToTorque(p, force, &tau));
  ASSERT_TRUE(kin.Inverse(p, &t0));
  ASSERT_TRUE(kin.Inverse(p + dp, &t1));
  EXPECT_NEAR(tau.dot(t1 - t0), force.dot(dp), 1e-4 * std::abs(force.dot(dp)));
  // Torques of a 9 N force are arm torques of order 0.1-1 N m.
  ASSERT_TRUE(kin.ForceToTorque(FalconCentre(), Eigen::Vector3d(0, 0, 9), &tau));
  EXPECT_LT(tau.cwiseAbs().maxCoeff(), 2.0);
  EXPECT_GT(tau.cwiseAbs().maxCoeff(), 0.05);
}

TEST(FalconKinematics, UnreachableAndNonFiniteInputsAreRejected) {
  FalconKinematics kin;
  Eigen::Vector3d theta(7, 7, 7), p;
  EXPECT_FALSE(kin.Inverse(Eigen::Vector3d(0, 0.5, 0.12), &theta));  // beyond the links
  EXPECT_EQ(theta, Eigen::Vector3d(7, 7, 7));
  EXPECT_FALSE(kin.Inverse(Eigen::Vector3d(std::nan(""), 0, 0.12), &theta));
  EXPECT_FALSE(kin.Inverse(Eigen::Vector3d(1e300, 0, 0.12), &theta));
  EXPECT_FALSE(kin.Forward(Eigen::Vector3d(std::nan(""), 0, 0), FalconCentre(), &p));
  EXPECT_TRUE(p.allFinite());
  Eigen::Vector3d tau;
  EXPECT_FALSE(kin.ForceToTorque(
      FalconCentre(), Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0), &tau));
}

TEST(FalconKinematics, ForwardFromAnglesNoPositionProducesFailsCleanly) {
  FalconKinematics kin;
  Eigen::Vector3d p;
  // Angles no configuration reaches: no convergence, but a finite answer.
  EXPECT_FALSE(kin.Forward(Eigen::Vector3d(3.0, -3.0, 3.0), FalconCentre(), &p));
  EXPECT_TRUE(p.allFinite());
}

TEST(FalconKinematics, TorqueCountsScaleAllThreeTogetherPast16Bits) {
  Eigen::Vector3d counts;
  EXPECT_EQ(TorqueCounts(Eigen::Vector3d(0.1, -0.2, 0.3), -10000, &counts), 1.0);
  EXPECT_TRUE(counts.isApprox(Eigen::Vector3d(-1000, 2000, -3000)));
  const double scale = TorqueCounts(Eigen::Vector3d(10, -5, 2), -10000, &counts);
  EXPECT_NEAR(scale, 32767.0 / 100000.0, 1e-12);
  EXPECT_NEAR(counts[0], -32767, 1e-9);
  EXPECT_NEAR(counts[1] / counts[0], -0.5, 1e-12);  // proportions kept
  EXPECT_NEAR(counts[2] / counts[0], 0.2, 1e-12);
}

}  // namespace
}  // namespace hapcine
