#include "estimate/geometry/model_selection.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace hapcine {
namespace {

constexpr double kPx = 1.0 / kReferenceWidthPx;  // one reference pixel, normalised units

struct Scene {
  std::vector<Eigen::Vector2d> u1, u2;
};

// Points at depth [near, far] seen by camera 1 (focal f1) and camera 2
// (X2 = R X1 + t, focal f2), normalised coordinates, Gaussian pixel noise.
Scene Make(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, double f1, double f2, double near,
           double far, double noise_px, unsigned seed, int n = 400) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.45, 0.45), d(near, far);
  std::normal_distribution<double> g(0, noise_px * kPx);
  Scene s;
  while (static_cast<int>(s.u1.size()) < n) {
    const double z = d(rng);
    const Eigen::Vector3d X(u(rng) * z / f1, u(rng) * 0.6 * z / f1, z);
    const Eigen::Vector3d X2 = R * X + t;
    if (X2.z() < 0.1) continue;
    const Eigen::Vector2d b = f2 * X2.hnormalized();
    if (std::abs(b.x()) > 0.5 || std::abs(b.y()) > 0.3) continue;
    s.u1.push_back(f1 * X.hnormalized() + Eigen::Vector2d(g(rng), g(rng)));
    s.u2.push_back(b + Eigen::Vector2d(g(rng), g(rng)));
  }
  return s;
}

Eigen::Matrix3d Pan(double deg) {
  return Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Eigen::Matrix3d Tilted(double deg) {
  return (Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(0.5 * deg * M_PI / 180, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

const double kF = 1.07;  // ~50 degrees horizontal FOV
const Eigen::Vector3d kZero = Eigen::Vector3d::Zero();

MotionModel Pick(const Scene& s, double f1 = kF) {
  return SelectTwoViewModel(s.u1, s.u2, f1, TwoViewOptions{}).model;
}

TEST(ModelSelection, Static) {
  EXPECT_EQ(Pick(Make(Eigen::Matrix3d::Identity(), kZero, kF, kF, 2, 20, 0.3, 1)), MotionModel::kStatic);
}

TEST(ModelSelection, TelephotoPanWithZoomFarFromThePriorFocalIsRotationZoom) {
  // 15 deg FOV (f = 3.8) while the estimator still holds the 50 deg prior
  // (the first window of a telephoto shot): a small pan with a 1 % zoom.
  const double f = 3.8;
  const Scene s = Make(Tilted(0.15), kZero, f, f * 1.01, 5, 50, 0.3, 21, 500);
  EXPECT_EQ(Pick(s, kF), MotionModel::kRotationZoom);
}

TEST(ModelSelection, Zoom) {
  EXPECT_EQ(Pick(Make(Eigen::Matrix3d::Identity(), kZero, kF, kF * 1.05, 2, 20, 0.3, 2)), MotionModel::kZoom);
}

TEST(ModelSelection, RotationWithDepthInTheScene) {
  EXPECT_EQ(Pick(Make(Tilted(3), kZero, kF, kF, 2, 20, 0.3, 3)), MotionModel::kRotation);
}

TEST(ModelSelection, RotationEvenWithAWrongFocalGuess) {
  const Scene s = Make(Tilted(8), kZero, kF, kF, 2, 20, 0.3, 4);
  const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, kF * 0.8, TwoViewOptions{});
  EXPECT_EQ(r.model, MotionModel::kRotation);
  EXPECT_NEAR(r.f1 / kF, 1.0, 0.02);  // self-calibrated
  EXPECT_EQ(r.translation, kZero);
}

TEST(ModelSelection, RotationPlusZoom) {
  EXPECT_EQ(Pick(Make(Tilted(3), kZero, kF, kF * 1.05, 2, 20, 0.3, 5)), MotionModel::kRotationZoom);
}

TEST(ModelSelection, GeneralWhenTranslatingInFrontOfDepth) {
  const Scene s = Make(Pan(1), Eigen::Vector3d(0.15, 0.02, 0), kF, kF, 2, 10, 0.3, 6);
  const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, kF, TwoViewOptions{});
  EXPECT_EQ(r.model, MotionModel::kGeneral);
  EXPECT_GT(r.translation.normalized().dot(Eigen::Vector3d(0.15, 0.02, 0).normalized()), 0.98);
}

TEST(ModelSelection, DollyIsNotAZoom) {
  EXPECT_EQ(Pick(Make(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.3), kF, kF, 2, 10, 0.3, 7)),
            MotionModel::kGeneral);
}

TEST(ModelSelection, PanOfAFarPlanarSceneIsRotation) {
  // A far plane: a translation is invisible, a homography fits, but the
  // rotation model is simpler and explains it.
  EXPECT_EQ(Pick(Make(Pan(4), kZero, kF, kF, 500, 500, 0.3, 8)), MotionModel::kRotation);
}

TEST(ModelSelection, TooFewPointsIsInvalidNotNaN) {
  const Scene s = Make(Pan(2), kZero, kF, kF, 2, 10, 0.3, 9, 5);
  const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, kF, TwoViewOptions{});
  EXPECT_FALSE(r.valid);
}

TEST(ModelSelection, OutliersDoNotChangeTheAnswer) {
  Scene s = Make(Tilted(3), kZero, kF, kF, 2, 20, 0.3, 10);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  for (size_t i = 0; i < s.u2.size() * 3 / 10; ++i) s.u2[i] = Eigen::Vector2d(u(rng), u(rng) * 0.6);
  EXPECT_EQ(Pick(s), MotionModel::kRotation);
}

TEST(ModelSelection, GricPenalisesParameters) {
  const std::vector<double> zero(100, 0.0);
  EXPECT_LT(Gric(zero, 1, 2, 0), Gric(zero, 1, 2, 4));
  EXPECT_LT(Gric(zero, 1, 2, 8), Gric(zero, 1, 3, 5));  // d = 3 costs n ln 4
}

TEST(ModelSelection, LongLensOrbitStepIsGeneral) {
  // An 11 degree lens (f = 5.19) stepping 23.5 degrees round an object 10
  // units away (X2 = R (X - O) + O): nearly affine views, where the
  // eight-point solver's projected minimal solutions are noise. A few dozen
  // descriptor matches with 1 px of noise, as between two stills.
  const double f = 5.19;
  const Eigen::Vector3d centre(0, 0, 10);
  const Eigen::Matrix3d R = Pan(23.5);
  for (unsigned seed : {41u, 42u, 43u}) {
    const Scene s = Make(R, (Eigen::Matrix3d::Identity() - R) * centre, f, f, 9.3, 10.7, 1.0, seed, 40);
    const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, f, TwoViewOptions{});
    EXPECT_EQ(r.model, MotionModel::kGeneral) << "seed " << seed;
    // Two near-affine views leave the step's angle ambiguous against the
    // depth relief (bas-relief); the window's bundle adjustment decides it.
    EXPECT_TRUE(std::isfinite(r.gric[kCandEssential])) << "seed " << seed;
    EXPECT_GE(r.num_inliers, 24) << "seed " << seed;
  }
}

}  // namespace
}  // namespace hapcine
