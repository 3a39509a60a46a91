#include "estimate/model_selection.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace hapcine {
namespace {

constexpr double kPx = 1.0 / 960;  // one pixel in normalised units

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

TwoViewOptions Anisotropic() {
  TwoViewOptions o;
  o.anisotropic_noise = true;
  return o;
}

TEST(ModelSelection, Static) {
  EXPECT_EQ(Pick(Make(Eigen::Matrix3d::Identity(), kZero, kF, kF, 2, 20, 0.3, 1)), MotionModel::kStatic);
}

TEST(ModelSelection, TelephotoPanWithZoomFarFromThePriorFocalIsRotationZoom) {
  // 15 deg FOV (f = 3.8) while the estimator still holds the 50 deg prior
  // (synth telephoto_zoom_pan's first window): a small pan with a 1 % zoom.
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

TEST(ModelSelection, GeneralWhenTranslatingInFrontOfDepthWithAnisotropicNoise) {
  // Depth changes from point to point here, so the parallax is irregular:
  // large parallax is above the largest believed noise (max_noise_sigma).
  const Scene s = Make(Pan(1), Eigen::Vector3d(0.15, 0.02, 0), kF, kF, 2, 10, 0.3, 6);
  EXPECT_EQ(SelectTwoViewModel(s.u1, s.u2, kF, Anisotropic()).model, MotionModel::kGeneral);
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

// Motion blur: the tracks of a pan are noisy along the pan (here 1.2 px
// more along x in view 2), not across it. An essential matrix with its
// epipole along x lets every match slide along x and, with one sigma
// measured across its lines, reads that noise as translation.
Scene BlurredAlongX(Scene s, double blur_px, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, blur_px * kPx);
  for (auto& u : s.u2) u.x() += g(rng);
  return s;
}

TEST(ModelSelection, BlurredPanIsRotationNotGeneral) {
  const Scene s = BlurredAlongX(Make(Pan(3), kZero, kF, kF, 2, 20, 0.25, 11), 1.2, 12);
  const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, kF, Anisotropic());
  EXPECT_EQ(r.model, MotionModel::kRotation);
  EXPECT_EQ(r.translation, kZero);
  EXPECT_NEAR(std::sqrt(r.noise_cov(0, 0)) / kPx, std::hypot(0.25, 1.2 / std::sqrt(2.0)), 0.2);
  // One isotropic sigma (the default) reads it as translation.
  EXPECT_EQ(SelectTwoViewModel(s.u1, s.u2, kF, TwoViewOptions{}).model, MotionModel::kGeneral);
}

TEST(ModelSelection, BlurredTranslationInFrontOfDepthStaysGeneral) {
  const Eigen::Vector3d t(0.15, 0.02, 0);
  const Scene s = BlurredAlongX(Make(Pan(1), t, kF, kF, 2, 10, 0.25, 13), 1.2, 14);
  const TwoViewResult r = SelectTwoViewModel(s.u1, s.u2, kF, Anisotropic());
  EXPECT_EQ(r.model, MotionModel::kGeneral);
  EXPECT_GT(r.translation.normalized().dot(t.normalized()), 0.95);
}

TEST(ModelSelection, TrackNoiseCovarianceIgnoresASmoothField) {
  // Residuals = a smooth field (parallax-like, up to 20 px) + per-view noise
  // 1 px along x and 0.3 px along y in both views.
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Vector2d> at, res;
  for (int i = 0; i < 600; ++i) {
    const Eigen::Vector2d x(u(rng), 0.6 * u(rng));
    const Eigen::Vector2d smooth(20 * kPx * std::sin(6 * x.x()), 10 * kPx * x.y() * x.x());
    const Eigen::Vector2d noise(std::sqrt(2.0) * 1.0 * kPx * g(rng), std::sqrt(2.0) * 0.3 * kPx * g(rng));
    at.push_back(x);
    res.push_back(smooth + noise);
  }
  const Eigen::Matrix2d cov = TrackNoiseCovariance(at, res, 8, 0.1 * kPx, 2 * kPx);
  EXPECT_NEAR(std::sqrt(cov(0, 0)) / kPx, 1.0, 0.15);
  EXPECT_NEAR(std::sqrt(cov(1, 1)) / kPx, 0.3, 0.06);
  EXPECT_NEAR(cov(0, 1) / (kPx * kPx), 0.0, 0.1);
  // Too few points to tell: the floor, isotropic.
  const std::vector<Eigen::Vector2d> few_at(at.begin(), at.begin() + 10), few_res(res.begin(), res.begin() + 10);
  EXPECT_EQ(TrackNoiseCovariance(few_at, few_res, 8, 0.5 * kPx, 2 * kPx), 0.25 * kPx * kPx * Eigen::Matrix2d::Identity());
  // Larger than any tracking noise: capped (it is structure, not noise).
  const Eigen::Matrix2d capped = TrackNoiseCovariance(at, res, 8, 0.1 * kPx, 0.5 * kPx);
  EXPECT_NEAR(std::sqrt(capped(0, 0)) / kPx, 0.5, 0.01);
  EXPECT_NEAR(std::sqrt(capped(1, 1)) / kPx, 0.3, 0.06);
}

TEST(ModelSelection, CheckRejectsBadNoiseOptions) {
  TwoViewOptions o;
  o.noise_neighbours = 0;
  EXPECT_THROW(o.Check(), UsageError);
  o = TwoViewOptions{};
  o.max_noise_sigma = 0;
  EXPECT_THROW(o.Check(), UsageError);
  EXPECT_NO_THROW(Anisotropic().Check());
}

TEST(ModelSelection, GricPenalisesParameters) {
  const std::vector<double> zero(100, 0.0);
  EXPECT_LT(Gric(zero, 1, 2, 0), Gric(zero, 1, 2, 4));
  EXPECT_LT(Gric(zero, 1, 2, 8), Gric(zero, 1, 3, 5));  // d = 3 costs n ln 4
}

}  // namespace
}  // namespace hapcine
