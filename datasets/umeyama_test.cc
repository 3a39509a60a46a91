#include "datasets/umeyama.h"

#include <gtest/gtest.h>

#include <random>

namespace hapcine {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, unsigned seed, double spread = 1.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, spread);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(g(rng), g(rng), g(rng));
  return pts;
}

bool AllFinite(const Sim3& t) {
  return std::isfinite(t.scale) && t.rotation.allFinite() && t.translation.allFinite();
}

TEST(UmeyamaTest, RecoversKnownSimilarity) {
  const auto src = RandomPoints(50, 1);
  Sim3 truth;
  truth.scale = 2.5;
  truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  truth.translation = {3, -1, 10};
  std::vector<Eigen::Vector3d> dst;
  for (const auto& p : src) dst.push_back(truth.Apply(p));

  const Sim3 fit = AlignUmeyama(src, dst, /*with_scale=*/true);
  EXPECT_NEAR(fit.scale, 2.5, 1e-9);
  EXPECT_TRUE(fit.rotation.isApprox(truth.rotation, 1e-9));
  EXPECT_TRUE(fit.translation.isApprox(truth.translation, 1e-9));
  EXPECT_NEAR(fit.rotation.determinant(), 1.0, 1e-12);
}

TEST(UmeyamaTest, RigidFitKeepsScaleOne) {
  const auto src = RandomPoints(20, 2);
  std::vector<Eigen::Vector3d> dst;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (const auto& p : src) dst.push_back(3.0 * (R * p));
  const Sim3 fit = AlignUmeyama(src, dst, /*with_scale=*/false);
  EXPECT_EQ(fit.scale, 1.0);
  EXPECT_TRUE(fit.rotation.isApprox(R, 1e-9));
}

TEST(UmeyamaTest, ReflectionIsNeverReturned) {
  // dst is a mirror image of src: the best proper rotation is not a reflection.
  const auto src = RandomPoints(30, 3);
  std::vector<Eigen::Vector3d> dst;
  for (const auto& p : src) dst.emplace_back(-p.x(), p.y(), p.z());
  const Sim3 fit = AlignUmeyama(src, dst, true);
  EXPECT_NEAR(fit.rotation.determinant(), 1.0, 1e-9);
  EXPECT_TRUE(AllFinite(fit));
}

TEST(UmeyamaTest, EmptyAndSinglePointGiveTranslationOnly) {
  const Sim3 empty = AlignUmeyama({}, {}, true);
  EXPECT_TRUE(AllFinite(empty));
  EXPECT_EQ(empty.scale, 1.0);

  const Sim3 one = AlignUmeyama({{1, 2, 3}}, {{4, 6, 8}}, true);
  EXPECT_TRUE(AllFinite(one));
  EXPECT_TRUE(one.Apply({1, 2, 3}).isApprox(Eigen::Vector3d(4, 6, 8)));
}

TEST(UmeyamaTest, AllSourcePointsEqualGivesNoNaN) {
  std::vector<Eigen::Vector3d> src(10, Eigen::Vector3d(1e6, 1e6, 1e6));
  const auto dst = RandomPoints(10, 4);
  const Sim3 fit = AlignUmeyama(src, dst, true);
  EXPECT_TRUE(AllFinite(fit));
  EXPECT_EQ(fit.scale, 1.0);
}

TEST(UmeyamaTest, AllTargetPointsEqualShrinksToThePoint) {
  // A rotation-only ground truth (camera never moves) against a drifting
  // estimate: Sim(3) maps everything onto the point, so ATE is 0 — which is
  // why the evaluator also reports the estimated path length.
  const auto src = RandomPoints(10, 5);
  std::vector<Eigen::Vector3d> dst(10, Eigen::Vector3d(0, 0, 0));
  const Sim3 fit = AlignUmeyama(src, dst, true);
  EXPECT_TRUE(AllFinite(fit));
  EXPECT_EQ(fit.scale, 0.0);
  for (const auto& p : src) EXPECT_LT(fit.Apply(p).norm(), 1e-12);
}

TEST(UmeyamaTest, CollinearPointsGiveFiniteExactFit) {
  std::vector<Eigen::Vector3d> src, dst;
  for (int i = 0; i < 10; ++i) {
    src.emplace_back(i, 0, 0);
    dst.emplace_back(0, 2.0 * i + 1, 0);
  }
  const Sim3 fit = AlignUmeyama(src, dst, true);
  ASSERT_TRUE(AllFinite(fit));
  EXPECT_NEAR(fit.scale, 2.0, 1e-9);
  EXPECT_NEAR(fit.rotation.determinant(), 1.0, 1e-9);
  for (size_t i = 0; i < src.size(); ++i) EXPECT_LT((fit.Apply(src[i]) - dst[i]).norm(), 1e-9);
}

TEST(UmeyamaTest, LargeCoordinatesStayAccurate) {
  auto src = RandomPoints(40, 6);
  std::vector<Eigen::Vector3d> dst;
  for (auto& p : src) {
    dst.push_back(p + Eigen::Vector3d(1e6, -2e6, 3e6));
    p += Eigen::Vector3d(1e6, 1e6, 1e6);
  }
  const Sim3 fit = AlignUmeyama(src, dst, true);
  EXPECT_NEAR(fit.scale, 1.0, 1e-6);
  for (size_t i = 0; i < src.size(); ++i) EXPECT_LT((fit.Apply(src[i]) - dst[i]).norm(), 1e-5);
}

}  // namespace
}  // namespace hapcine
