#include "estimate/geometry/two_view_estimators.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "estimate/geometry/ransac.h"
#include "estimate/geometry/two_view_geometry.h"

namespace hapcine {
namespace {

// Calibrated correspondences (OpenCV axes) of random points 2..10 deep.
struct Pairs {
  std::vector<Eigen::Vector2d> c1, c2;
};

Pairs MakePairs(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, int n, double noise,
                double outliers, unsigned seed, double plane_depth = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5), d(2, 10);
  std::normal_distribution<double> g(0, noise);
  Pairs p;
  while (static_cast<int>(p.c1.size()) < n) {
    const double z = plane_depth > 0 ? plane_depth : d(rng);
    const Eigen::Vector3d X(u(rng) * z, u(rng) * z, z);
    const Eigen::Vector3d X2 = R * X + t;
    if (X2.z() < 0.1) continue;
    Eigen::Vector2d a = X.hnormalized(), b = X2.hnormalized();
    if (noise > 0) {
      a += Eigen::Vector2d(g(rng), g(rng));
      b += Eigen::Vector2d(g(rng), g(rng));
    }
    if (static_cast<int>(p.c1.size()) < outliers * n) b = Eigen::Vector2d(u(rng), u(rng));
    p.c1.push_back(a);
    p.c2.push_back(b);
  }
  return p;
}

Eigen::Matrix3d Rot(double ax, double ay, double az) {
  return (Eigen::AngleAxisd(ax, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(ay, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(az, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180 / M_PI;
}

RansacOptions Opts(double thr) {
  RansacOptions o;
  o.max_error = thr;
  return o;
}

TEST(RotationEstimator, ExactRecoveryFromMinimalSample) {
  const Eigen::Matrix3d R = Rot(0.1, -0.2, 0.05);
  const Pairs p = MakePairs(R, Eigen::Vector3d::Zero(), 2, 0, 0, 1);
  const auto models = RotationEstimator::Estimate(p.c1, p.c2);
  ASSERT_EQ(models.size(), 1u);
  EXPECT_LT(AngleDeg(models[0], R), 1e-9);
}

TEST(RotationEstimator, RansacWithOutliersAndNoise) {
  const Eigen::Matrix3d R = Rot(0.02, 0.3, -0.1);
  const Pairs p = MakePairs(R, Eigen::Vector3d::Zero(), 300, 0.5 / 1000, 0.3, 2);
  const auto rep = Ransac<RotationEstimator>(p.c1, p.c2, Opts(2.0 / 1000));
  ASSERT_TRUE(rep.success);
  EXPECT_LT(AngleDeg(rep.model, R), 0.01);
  EXPECT_NEAR(rep.num_inliers, 210, 10);
  for (int i = 0; i < 90; ++i) EXPECT_FALSE(rep.inlier_mask[i]) << i;
}

TEST(RotationEstimator, DegenerateSampleGivesNoModel) {
  const std::vector<Eigen::Vector2d> same = {{0.1, 0.2}, {0.1, 0.2}};
  EXPECT_TRUE(RotationEstimator::Estimate(same, same).empty());
  const std::vector<Eigen::Vector2d> nan = {{NAN, 0.2}, {0.1, 0.2}};
  EXPECT_TRUE(RotationEstimator::Estimate(nan, nan).empty());
}

TEST(RotationZoomEstimator, RecoversRotationAndSecondFocal) {
  const Eigen::Matrix3d R = Rot(0.05, 0.15, 0.02);
  const double f2 = 1.3;
  Pairs p = MakePairs(R, Eigen::Vector3d::Zero(), 200, 0, 0, 3);
  for (auto& x : p.c2) x *= f2;  // view 2 in normalised units
  const auto minimal = RotationZoomEstimator::Estimate({p.c1[0], p.c1[1]}, {p.c2[0], p.c2[1]});
  ASSERT_FALSE(minimal.empty());
  bool found = false;
  for (const auto& m : minimal) found |= std::abs(m.f2 - f2) < 1e-8 && AngleDeg(m.cam2_from_cam1, R) < 1e-6;
  EXPECT_TRUE(found);
  Pairs q = MakePairs(R, Eigen::Vector3d::Zero(), 300, 0.5 / 1000, 0.3, 4);
  for (auto& x : q.c2) x *= f2;
  const auto rep = Ransac<RotationZoomEstimator>(q.c1, q.c2, Opts(2.0 / 1000));
  ASSERT_TRUE(rep.success);
  EXPECT_NEAR(rep.model.f2, f2, 0.01);
  EXPECT_LT(AngleDeg(rep.model.cam2_from_cam1, R), 0.05);
}

TEST(ZoomEstimator, RecoversScaleAndRejectsCentre) {
  std::vector<Eigen::Vector2d> a = {{0.1, 0.2}, {-0.3, 0.1}, {0.2, -0.2}}, b;
  for (const auto& x : a) b.push_back(1.25 * x);
  const auto m = ZoomEstimator::Estimate(a, b);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0], 1.25, 1e-12);
  EXPECT_TRUE(ZoomEstimator::Estimate({{0, 0}}, {{0, 0}}).empty());
}

TEST(HomographyEstimator, ExactWithOutliersAndScaledCoordinates) {
  Eigen::Matrix3d H;
  H << 1.1, 0.05, 20, -0.03, 0.95, -10, 1e-4, -2e-4, 1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1000);
  std::normal_distribution<double> g(0, 0.5);
  for (double scale : {1.0, 1e3}) {
    std::vector<Eigen::Vector2d> x1, x2;
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector2d p(u(rng), u(rng));
      Eigen::Vector2d q = (H * p.homogeneous()).hnormalized() + Eigen::Vector2d(g(rng), g(rng));
      if (i < 90) q = Eigen::Vector2d(u(rng), u(rng));
      x1.push_back(p * scale);
      x2.push_back(q * scale);
    }
    const auto rep = Ransac<HomographyEstimator>(x1, x2, Opts(2.0 * scale));
    ASSERT_TRUE(rep.success);
    EXPECT_NEAR(rep.num_inliers, 210, 8);
    const Eigen::Vector2d p(500, 500);
    const Eigen::Vector2d expect = (H * p.homogeneous()).hnormalized() * scale;
    const Eigen::Vector2d got = (rep.model * (p * scale).homogeneous()).hnormalized();
    EXPECT_LT((got - expect).norm(), 0.5 * scale);
  }
}

TEST(HomographyEstimator, ExactFromMinimalSampleAtAnyScale) {
  // Four points: the 8 x 9 DLT system's null vector (QR, not SVD) is the
  // homography itself, to round-off, in pixel and in normalised units.
  Eigen::Matrix3d H;
  H << 0.9, -0.1, 35, 0.08, 1.05, -12, -2e-4, 1e-4, 1;
  H /= H.norm();
  for (double scale : {1e-3, 1.0, 1e4}) {
    std::vector<Eigen::Vector2d> x1 = {{10, 20}, {900, 40}, {850, 700}, {30, 650}}, x2;
    for (auto& p : x1) {
      p *= scale;
      Eigen::Matrix3d S = Eigen::Vector3d(scale, scale, 1).asDiagonal();
      x2.push_back((S * H * S.inverse() * p.homogeneous()).hnormalized());
    }
    const auto m = HomographyEstimator::Estimate(x1, x2);
    ASSERT_EQ(m.size(), 1u) << scale;
    std::vector<double> r;
    HomographyEstimator::Residuals(x1, x2, m[0], &r);
    for (double v : r) EXPECT_LT(std::sqrt(v), 1e-9 * scale) << scale;
  }
}

TEST(HomographyEstimator, CollinearPointsGiveNoModel) {
  const std::vector<Eigen::Vector2d> x = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_TRUE(HomographyEstimator::Estimate(x, x).empty());
}

TEST(EssentialEstimator, RecoversPoseExactAndRobust) {
  const Eigen::Matrix3d R = Rot(0.05, -0.1, 0.02);
  const Eigen::Vector3d t = Eigen::Vector3d(0.8, 0.1, 0.3).normalized();
  const Pairs exact = MakePairs(R, t, 8, 0, 0, 6);
  const auto m = EssentialEstimator::Estimate(exact.c1, exact.c2);
  ASSERT_EQ(m.size(), 1u);
  Eigen::Matrix3d Rr;
  Eigen::Vector3d tr;
  ASSERT_TRUE(DecomposeEssential(m[0], exact.c1, exact.c2, &Rr, &tr));
  EXPECT_LT(AngleDeg(Rr, R), 1e-6);
  EXPECT_LT((tr - t).norm(), 1e-6);

  const Pairs noisy = MakePairs(R, t, 400, 0.5 / 1000, 0.3, 7);
  const auto rep = Ransac<EssentialEstimator>(noisy.c1, noisy.c2, Opts(2.0 / 1000));
  ASSERT_TRUE(rep.success);
  std::vector<Eigen::Vector2d> a, b;
  for (size_t i = 0; i < noisy.c1.size(); ++i)
    if (rep.inlier_mask[i]) {
      a.push_back(noisy.c1[i]);
      b.push_back(noisy.c2[i]);
    }
  ASSERT_TRUE(DecomposeEssential(rep.model, a, b, &Rr, &tr));
  EXPECT_LT(AngleDeg(Rr, R), 0.2);
  EXPECT_GT(tr.dot(t), 0.99);
}

TEST(EssentialEstimator, DegenerateInputGivesNoModelNoNaN) {
  std::vector<Eigen::Vector2d> same(8, Eigen::Vector2d(0.1, 0.1));
  EXPECT_TRUE(EssentialEstimator::Estimate(same, same).empty());
  std::vector<double> r;
  EssentialEstimator::Residuals(same, same, Eigen::Matrix3d::Zero(), &r);
  for (double v : r) EXPECT_FALSE(std::isnan(v));
}

TEST(FitRotationAndFocal, SelfCalibratesFocalFromAPan) {
  const Eigen::Matrix3d R = Rot(0.02, 0.2, 0.0);
  const double f = 1.2;
  Pairs p = MakePairs(R, Eigen::Vector3d::Zero(), 200, 0, 0, 8);
  for (auto& x : p.c1) x *= f;
  for (auto& x : p.c2) x *= f;
  double f_est;
  Eigen::Matrix3d R_est;
  FitRotationAndFocal(p.c1, p.c2, 0.9, 2.0, &f_est, &R_est);
  EXPECT_NEAR(f_est, f, 1e-4);
  EXPECT_LT(AngleDeg(R_est, R), 1e-3);
}

}  // namespace
}  // namespace hapcine
