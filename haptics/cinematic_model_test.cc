#include "haptics/cinematic_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using testing::MakeEffectPath;
constexpr int H = 0, L = 1, R = 2;

WashoutOptions NoWashout() {
  WashoutOptions w;
  w.mode = WashoutMode::kOff;
  return w;
}

std::vector<ActuatorFrame> Model(const CameraPath& path, const WashoutOptions& w,
                                 const CinematicOptions& o = CinematicOptions()) {
  const SeatGeometry seat;
  return CinematicFrames(path, seat, o, w, ComputeCinematicScaling(path, seat, o, w));
}

double MaxCoord(const std::vector<ActuatorFrame>& v) {
  double m = 0;
  for (const auto& f : v)
    for (const auto& a : f) m = std::max(m, a.cwiseAbs().maxCoeff());
  return m;
}

TEST(CinematicModel, CombinationIsEquation3) {
  const SeatGeometry seat;
  CinematicScale c;
  c.kx = c.ky = c.kz = c.sz = 0.01;
  c.mx = c.my = c.mz = 1;
  // All zero -> zero (no division by zero).
  for (const auto& a : CinematicDisplacement(Eigen::Vector3d::Zero(), 0, 0, 0, 0, c, seat)) {
    EXPECT_EQ(a, Eigen::Vector3d::Zero());
  }
  // T alone -> T for every actuator.
  const auto t = CinematicDisplacement(Eigen::Vector3d(1, 2, 3), 0, 0, 0, 0, c, seat);
  for (const auto& a : t) EXPECT_TRUE(a.isApprox(Eigen::Vector3d(0.01, 0.02, 0.03)));
  // T and F: weighted by their norms.
  const auto tf = CinematicDisplacement(Eigen::Vector3d(1, 0, 0), 0, 0, 0, 3.0, c, seat);
  const Eigen::Vector3d T(0.01, 0, 0), F(0, 0, -0.03);
  EXPECT_TRUE(tf[0].isApprox((0.01 * T + 0.03 * F) / 0.04));
}

TEST(CinematicModel, VertigoGivesNoMovement) {
  const CameraPath path = MakeEffectPath(CameraEffect::kVertigo);
  for (const WashoutOptions& w : {NoWashout(), WashoutOptions()}) {
    EXPECT_LT(MaxCoord(Model(path, w)), 1e-7);  // 100 nm: the FOVs are floats (~1e-7 of their value)
  }
}

TEST(CinematicModel, ZoomInIsAForwardMovementUsingTheWorkspace) {
  const auto v = Model(MakeEffectPath(CameraEffect::kZoomIn), NoWashout());
  for (int a = 0; a < kNumActuators; ++a) {
    EXPECT_NEAR(v.back()[a].z(), -SeatGeometry().usable_half_m, 1e-9);  // forward = -Z
    EXPECT_NEAR(v.back()[a].x(), 0, 1e-12);
    EXPECT_NEAR(v.back()[a].y(), 0, 1e-12);
  }
  // A zoom-out goes backward.
  const auto out = Model(MakeEffectPath(CameraEffect::kZoomIn, -0.5), NoWashout());
  EXPECT_GT(out.back()[H].z(), 0.01);
}

TEST(CinematicModel, DutchAngleMovesLeftHandDownRightHandUp) {
  const auto v = Model(MakeEffectPath(CameraEffect::kDutchAngle), NoWashout());
  EXPECT_LT(v.back()[L].y(), -0.01);
  EXPECT_GT(v.back()[R].y(), 0.01);
  EXPECT_NEAR(MaxCoord(v), SeatGeometry().usable_half_m, 1e-6);
}

TEST(CinematicModel, TravelingMovesAllThreeSidewaysTogether) {
  const auto v = Model(MakeEffectPath(CameraEffect::kTraveling), NoWashout());
  for (const auto& f : v) {
    EXPECT_NEAR(f[H].x(), f[L].x(), 1e-12);
    EXPECT_NEAR(f[H].x(), f[R].x(), 1e-12);
    EXPECT_NEAR(f[H].y(), 0, 1e-12);
    EXPECT_NEAR(f[H].z(), 0, 1e-12);
  }
  EXPECT_NEAR(v.back()[H].x(), SeatGeometry().usable_half_m, 1e-9);
  // Traveling left goes left.
  EXPECT_LT(Model(MakeEffectPath(CameraEffect::kTraveling, -1), NoWashout()).back()[R].x(), -0.01);
}

TEST(CinematicModel, TiltingRotatesAboutTheChest) {
  const SeatGeometry seat;
  const auto v = Model(MakeEffectPath(CameraEffect::kTilting), NoWashout());
  for (const auto& f : v) {
    for (int a = 0; a < kNumActuators; ++a) {
      // A rotation about G keeps every actuator's distance to G.
      EXPECT_NEAR((seat.FromCenter(a) + f[a]).norm(), seat.FromCenter(a).norm(), 1e-12);
      EXPECT_NEAR(f[a].x(), 0, 1e-12);  // in the vertical plane
    }
  }
  // Tilting up (the view turns up): like leaning back, the head goes backward.
  EXPECT_GT(v.back()[H].z(), 0.01);
  EXPECT_NEAR(MaxCoord(v), seat.usable_half_m, 1e-6);
}

TEST(CinematicModel, CraneShotLiftsEveryone) {
  const auto v = Model(MakeEffectPath(CameraEffect::kCraneShot), NoWashout());
  for (int a = 0; a < kNumActuators; ++a) EXPECT_GT(v.back()[a].y(), 0.01);
}

TEST(CinematicModel, NeverLeavesTheUsableRange) {
  for (int e = 1; e < kNumCameraEffects; ++e) {
    for (double noise : {0.0, 0.01}) {
      testing::EffectPathSpec s;
      s.effect = static_cast<CameraEffect>(e);
      s.noise = noise;
      const CameraPath path = MakeEffectPath(s);
      for (const WashoutOptions& w : {NoWashout(), WashoutOptions()}) {
        const auto v = Model(path, w);
        EXPECT_LE(MaxCoord(v), SeatGeometry().usable_half_m + 1e-9) << EffectName(s.effect);
        for (const auto& f : v)
          for (const auto& a : f) ASSERT_TRUE(a.allFinite());
      }
    }
  }
}

TEST(CinematicModel, IndependentOfTheWorldFrame) {
  const CameraPath path = MakeEffectPath(CameraEffect::kArcing);
  const CameraPath moved = testing::TransformWorld(
      path, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d(100, -20, 5));
  const auto a = Model(path, WashoutOptions()), b = Model(moved, WashoutOptions());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    for (int k = 0; k < kNumActuators; ++k) EXPECT_LT((a[i][k] - b[i][k]).norm(), 1e-9);
  }
}

TEST(CinematicModel, GainCapsKeepNoiseSmall) {
  testing::EffectPathSpec s;  // a still shot with estimator-like jitter
  s.noise = 1e-4;
  const CameraPath path = MakeEffectPath(s);
  const auto v = Model(path, NoWashout());
  EXPECT_LT(MaxCoord(v), 2e-3);  // not blown up to the 0.045 m range
  const SeatGeometry seat;
  const CinematicScaling sc = ComputeCinematicScaling(path, seat, CinematicOptions(), NoWashout());
  EXPECT_DOUBLE_EQ(sc.per_shot[0].kx, CinematicOptions().max_translation_gain);
  EXPECT_DOUBLE_EQ(sc.per_shot[0].mx, CinematicOptions().max_rotation_gain);
}

TEST(CinematicModel, PerFilmScalingTakesTheSmallestFactors) {
  CameraPath a = MakeEffectPath(CameraEffect::kTraveling, 1.0);
  const CameraPath b = MakeEffectPath(CameraEffect::kTraveling, 3.0);
  const double offset = a.frames.back().time_s + 1.0 / 30;
  for (auto f : b.frames) {
    f.frame += static_cast<int>(a.frames.size());
    f.time_s += offset;
    f.shot = 1;
    a.frames.push_back(f);
  }
  for (size_t i = 0; i < a.frames.size() - b.frames.size(); ++i) a.frames[i].shot = 0;
  const SeatGeometry seat;
  CinematicOptions o;
  const auto per_shot = ComputeCinematicScaling(a, seat, o, NoWashout());
  ASSERT_EQ(per_shot.per_shot.size(), 2u);
  EXPECT_NEAR(per_shot.per_shot[0].kx, 3 * per_shot.per_shot[1].kx, 1e-9);
  o.per_film_scaling = true;
  const auto film = ComputeCinematicScaling(a, seat, o, NoWashout());
  EXPECT_DOUBLE_EQ(film.per_shot[0].kx, per_shot.per_shot[1].kx);
  EXPECT_DOUBLE_EQ(film.ForShot(7).kx, per_shot.per_shot[1].kx);  // extra shots reuse the last
}

}  // namespace
}  // namespace hapcine
