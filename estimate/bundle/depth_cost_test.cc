#include "estimate/bundle/depth_cost.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <random>
#include <string>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {
namespace {

struct Params {
  std::array<double, 4> q;
  std::array<double, 3> c;
  double lf;
  std::array<double, 4> X;
  const double* ptrs[4] = {q.data(), c.data(), &lf, X.data()};
};

Params Random(std::mt19937* rng, double rho) {
  std::normal_distribution<double> g(0, 1);
  Params p;
  // A camera looking roughly along +z at points in front of it.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * g(*rng), Eigen::Vector3d(g(*rng), g(*rng), g(*rng)).normalized()));
  p.q = {q.x(), q.y(), q.z(), q.w()};
  p.c = {0.2 * g(*rng), 0.2 * g(*rng), 0.2 * g(*rng)};
  p.lf = std::log(0.8 + 0.1 * g(*rng));
  const Eigen::Vector3d d = q * Eigen::Vector3d(0.3 * g(*rng), 0.3 * g(*rng), 1).normalized();
  Eigen::Vector4d X(d.x(), d.y(), d.z(), rho);
  X.normalize();
  p.X = {X(0), X(1), X(2), X(3)};
  return p;
}

// Analytic Jacobians of `cost` at `blocks` against central differences (a
// forward one for a coordinate at the bound 0 of its domain, flagged in `at_bound`).
void ExpectJacobiansMatch(const ceres::CostFunction& cost, const std::vector<double*>& blocks,
                          const std::vector<int>& sizes, const double* at_bound, const std::string& what) {
  double r[2];
  std::vector<std::vector<double>> J(blocks.size());
  std::vector<double*> jac(blocks.size());
  for (size_t k = 0; k < blocks.size(); ++k) {
    J[k].assign(2 * sizes[k], 0);
    jac[k] = J[k].data();
  }
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r, jac.data()));
  const double h = 1e-6;
  for (size_t k = 0; k < blocks.size(); ++k) {
    for (int i = 0; i < sizes[k]; ++i) {
      double rp[2], rm[2];
      const double keep = blocks[k][i];
      blocks[k][i] = keep + h;
      ASSERT_TRUE(cost.Evaluate(blocks.data(), rp, nullptr));
      const bool forward = &blocks[k][i] == at_bound && keep < h;
      blocks[k][i] = forward ? keep : keep - h;
      ASSERT_TRUE(cost.Evaluate(blocks.data(), rm, nullptr));
      blocks[k][i] = keep;
      for (int row = 0; row < 2; ++row) {
        const double numeric = (rp[row] - rm[row]) / (forward ? h : 2 * h);
        EXPECT_NEAR(J[k][row * sizes[k] + i], numeric, (forward ? 1e-4 : 1e-5) * (1 + std::abs(numeric)))
            << what << " block " << k << " coord " << i << " row " << row;
      }
    }
  }
}

TEST(DepthCostFunction, JacobiansMatchCentralDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    Params p = Random(&rng, trial % 5 == 0 ? 0.0 : 0.05 + 0.1 * (trial % 7));
    const DepthCostFunction cost(Eigen::Vector2d(0.01, -0.02), Eigen::Vector3d(0.1, -0.1, 0.05), 960);
    ExpectJacobiansMatch(cost, {p.q.data(), p.c.data(), &p.lf, p.X.data()}, {4, 3, 1, 4}, &p.X[3],
                         "trial " + std::to_string(trial));
    if (p.X[3] == 0) {  // a point at infinity does not move with the centre
      double r[2], jc[6];
      double* jac[4] = {nullptr, jc, nullptr, nullptr};
      ASSERT_TRUE(cost.Evaluate(p.ptrs, r, jac));
      for (double v : jc) EXPECT_EQ(v, 0.0);
    }
  }
}

TEST(PoseDepthCostFunction, AgreesWithTheSplitBlocks) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    Params p = Random(&rng, trial % 4 == 0 ? 0.0 : 0.1 + 0.2 * (trial % 3));
    const Eigen::Vector2d u(0.02, -0.01);
    const Eigen::Vector3d anchor(-0.2, 0.1, 0.3);
    const DepthCostFunction split(u, anchor, 960);
    const PoseDepthCostFunction merged(u, anchor, 960);
    std::array<double, 7> pose = {p.q[0], p.q[1], p.q[2], p.q[3], p.c[0], p.c[1], p.c[2]};
    ExpectJacobiansMatch(merged, {pose.data(), &p.lf, p.X.data()}, {7, 1, 4}, &p.X[3],
                         "trial " + std::to_string(trial));
    double rs[2], rm[2], jq[8], jc[6], jf_s[2], jx_s[8], jp[14], jf_m[2], jx_m[8];
    double* jac_s[4] = {jq, jc, jf_s, jx_s};
    double* jac_m[3] = {jp, jf_m, jx_m};
    const double* merged_blocks[3] = {pose.data(), &p.lf, p.X.data()};
    ASSERT_TRUE(split.Evaluate(p.ptrs, rs, jac_s));
    ASSERT_TRUE(merged.Evaluate(merged_blocks, rm, jac_m));
    for (int r = 0; r < 2; ++r) {
      EXPECT_EQ(rs[r], rm[r]);
      EXPECT_EQ(jf_s[r], jf_m[r]);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(jq[4 * r + k], jp[7 * r + k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(jc[3 * r + k], jp[7 * r + 4 + k]);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(jx_s[4 * r + k], jx_m[4 * r + k]);
    }
  }
  Params behind = Random(&rng, 0.1);
  behind.X[3] = -0.1;  // beyond infinity
  std::array<double, 7> pose = {behind.q[0], behind.q[1], behind.q[2], behind.q[3], 0, 0, 0};
  const double* blocks[3] = {pose.data(), &behind.lf, behind.X.data()};
  double r[2];
  EXPECT_FALSE(PoseDepthCostFunction(Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero(), 960)
                   .Evaluate(blocks, r, nullptr));
}

TEST(PoseFocalDepthCostFunction, AgreesWithTheSplitBlocks) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    Params p = Random(&rng, trial % 4 == 0 ? 0.0 : 0.1 + 0.2 * (trial % 3));
    const Eigen::Vector2d u(-0.03, 0.02);
    const Eigen::Vector3d anchor(0.1, -0.2, 0.4);
    const DepthCostFunction split(u, anchor, 960);
    const PoseFocalDepthCostFunction merged(u, anchor, 960);
    std::array<double, 8> pose = {p.q[0], p.q[1], p.q[2], p.q[3], p.c[0], p.c[1], p.c[2], p.lf};
    ExpectJacobiansMatch(merged, {pose.data(), p.X.data()}, {8, 4}, &p.X[3],
                         "trial " + std::to_string(trial));
    double rs[2], rm[2], jq[8], jc[6], jf[2], jx_s[8], jp[16], jx_m[8];
    double* jac_s[4] = {jq, jc, jf, jx_s};
    double* jac_m[2] = {jp, jx_m};
    const double* merged_blocks[2] = {pose.data(), p.X.data()};
    ASSERT_TRUE(split.Evaluate(p.ptrs, rs, jac_s));
    ASSERT_TRUE(merged.Evaluate(merged_blocks, rm, jac_m));
    for (int r = 0; r < 2; ++r) {
      EXPECT_EQ(rs[r], rm[r]);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(jq[4 * r + k], jp[8 * r + k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(jc[3 * r + k], jp[8 * r + 4 + k]);
      EXPECT_EQ(jf[r], jp[8 * r + 7]);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(jx_s[4 * r + k], jx_m[4 * r + k]);
    }
  }
  Params behind = Random(&rng, 0.1);
  behind.X[3] = -0.1;  // beyond infinity
  std::array<double, 8> pose = {behind.q[0], behind.q[1], behind.q[2], behind.q[3], 0, 0, 0, behind.lf};
  const double* blocks[2] = {pose.data(), behind.X.data()};
  double r[2];
  EXPECT_FALSE(PoseFocalDepthCostFunction(Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero(), 960)
                   .Evaluate(blocks, r, nullptr));
}

TEST(BearingCostFunction, JacobiansMatchCentralDifferences) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    Params p = Random(&rng, 0.0);
    const BearingCostFunction cost(Eigen::Vector2d(-0.03, 0.02), 960);
    ExpectJacobiansMatch(cost, {p.q.data(), &p.lf, p.X.data()}, {4, 1, 3}, nullptr,
                         "trial " + std::to_string(trial));
  }
}

TEST(BearingCostFunction, AgreesWithTheDepthResidualAtInfinity) {
  std::mt19937 rng(13);
  Params p = Random(&rng, 0.0);
  const Eigen::Vector2d u(0.02, 0.01);
  const DepthCostFunction depth(u, Eigen::Vector3d(1, 2, 3), 960);
  const BearingCostFunction bearing(u, 960);
  const double* bearing_blocks[3] = {p.q.data(), &p.lf, p.X.data()};
  double rd[2], rb[2];
  ASSERT_TRUE(depth.Evaluate(p.ptrs, rd, nullptr));
  ASSERT_TRUE(bearing.Evaluate(bearing_blocks, rb, nullptr));
  EXPECT_NEAR(rd[0], rb[0], 1e-12);
  EXPECT_NEAR(rd[1], rb[1], 1e-12);
  for (int i = 0; i < 3; ++i) p.X[i] = -p.X[i];  // behind the camera
  EXPECT_FALSE(bearing.Evaluate(bearing_blocks, rb, nullptr));
}

TEST(DepthCostFunction, ResidualAgreesWithObservationErrors) {
  std::mt19937 rng(3);
  const Params p = Random(&rng, 0.2);
  BaCamera cam;
  cam.world_from_cam = Eigen::Quaterniond(p.q[3], p.q[0], p.q[1], p.q[2]);
  cam.center = Eigen::Vector3d(p.c[0], p.c[1], p.c[2]);
  cam.log_focal = p.lf;
  BaPoint pt;
  pt.anchor = Eigen::Vector3d(0.1, -0.1, 0.05);
  pt.homogeneous = Eigen::Vector4d(p.X[0], p.X[1], p.X[2], p.X[3]);
  const Eigen::Vector2d u(0.01, -0.02);
  const double inv_scale = 960;
  const DepthCostFunction cost(u, pt.anchor, inv_scale);
  double r[2];
  ASSERT_TRUE(cost.Evaluate(p.ptrs, r, nullptr));
  const double err = ObservationErrors({cam}, {pt}, {{0, 0, u}}, true)[0];
  EXPECT_NEAR(std::hypot(r[0], r[1]) / inv_scale, err, 1e-12);
}

TEST(DepthCostFunction, FailsBeyondInfinityAndBehindTheCamera) {
  std::mt19937 rng(5);
  Params p = Random(&rng, 0.1);
  const DepthCostFunction cost(Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero(), 960);
  double r[2];
  EXPECT_TRUE(cost.Evaluate(p.ptrs, r, nullptr));
  p.X[3] = -0.1;
  EXPECT_FALSE(cost.Evaluate(p.ptrs, r, nullptr));
  p.X[3] = 0;
  for (int i = 0; i < 3; ++i) p.X[i] = -p.X[i];  // direction reversed: behind
  EXPECT_FALSE(cost.Evaluate(p.ptrs, r, nullptr));
}

}  // namespace
}  // namespace hapcine
