#include "estimate/depth_cost.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <random>
#include <vector>

#include "estimate/bundle_adjustment.h"

namespace hapcine {
namespace {

struct Params {
  std::array<double, 4> q;
  std::array<double, 3> c;
  double lf;
  std::array<double, 4> X;
  const double* ptrs[4] = {q.data(), c.data(), &lf, X.data()};
  double* block(int k) { return const_cast<double*>(ptrs[k]); }
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

constexpr int kSizes[4] = {4, 3, 1, 4};

TEST(DepthCostFunction, JacobiansMatchCentralDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    Params p = Random(&rng, trial % 5 == 0 ? 0.0 : 0.05 + 0.1 * (trial % 7));
    const DepthCostFunction cost(Eigen::Vector2d(0.01, -0.02), Eigen::Vector3d(0.1, -0.1, 0.05), 960);
    double r[2];
    std::vector<std::vector<double>> J(4);
    double* jac[4];
    for (int k = 0; k < 4; ++k) {
      J[k].assign(2 * kSizes[k], 0);
      jac[k] = J[k].data();
    }
    ASSERT_TRUE(cost.Evaluate(p.ptrs, r, jac));
    const double h = 1e-6;
    for (int k = 0; k < 4; ++k) {
      for (int i = 0; i < kSizes[k]; ++i) {
        double rp[2], rm[2];
        const double keep = p.block(k)[i];
        p.block(k)[i] = keep + h;
        ASSERT_TRUE(cost.Evaluate(p.ptrs, rp, nullptr));
        // rho = 0 is the bound of the domain: a forward difference there.
        const bool forward = k == 3 && i == 3 && keep < h;
        p.block(k)[i] = forward ? keep : keep - h;
        ASSERT_TRUE(cost.Evaluate(p.ptrs, rm, nullptr));
        p.block(k)[i] = keep;
        for (int row = 0; row < 2; ++row) {
          const double numeric = (rp[row] - rm[row]) / (forward ? h : 2 * h);
          EXPECT_NEAR(J[k][row * kSizes[k] + i], numeric, (forward ? 1e-4 : 1e-5) * (1 + std::abs(numeric)))
              << "trial " << trial << " block " << k << " coord " << i << " row " << row;
        }
      }
    }
    // A point at infinity does not move with the centre.
    if (p.X[3] == 0)
      for (double v : J[1]) EXPECT_EQ(v, 0.0);
  }
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
