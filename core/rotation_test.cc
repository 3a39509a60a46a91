#include "core/rotation.h"

#include <gtest/gtest.h>

#include <random>

namespace hapcine {
namespace {

TEST(RotationTest, PanTiltRollRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pan(-179, 179), tilt(-89, 89), roll(-179, 179);
  for (int i = 0; i < 1000; ++i) {
    const PanTiltRoll a{pan(rng), tilt(rng), roll(rng)};
    const PanTiltRoll b = PanTiltRollFromQuaternion(QuaternionFromPanTiltRoll(a));
    EXPECT_NEAR(a.pan_deg, b.pan_deg, 1e-7);
    EXPECT_NEAR(a.tilt_deg, b.tilt_deg, 1e-7);
    EXPECT_NEAR(a.roll_deg, b.roll_deg, 1e-7);
  }
}

TEST(RotationTest, GimbalLockGivesFiniteAnglesThatReproduceTheRotation) {
  for (double tilt : {90.0, -90.0}) {
    const Eigen::Quaterniond q = QuaternionFromPanTiltRoll({30, tilt, 10});
    const PanTiltRoll a = PanTiltRollFromQuaternion(q);
    EXPECT_TRUE(std::isfinite(a.pan_deg) && std::isfinite(a.roll_deg));
    EXPECT_LT(AngleBetweenDeg(q, QuaternionFromPanTiltRoll(a)), 1e-4);
  }
}

TEST(RotationTest, CanonicalQuaternionHasNonNegativeW) {
  const Eigen::Quaterniond q(-0.5, 0.5, -0.5, 0.5);
  const Eigen::Quaterniond c = CanonicalQuaternion(q);
  EXPECT_GE(c.w(), 0);
  EXPECT_NEAR(c.norm(), 1, 1e-15);
  EXPECT_LT(AngleBetweenDeg(q, c), 1e-9);
}

TEST(RotationTest, TinyAnglesAreAccurate) {
  // acos(w) would lose everything below ~1e-6 degrees; atan2 keeps it.
  const Eigen::Quaterniond q = QuaternionFromPanTiltRoll({1e-7, 0, 0});
  EXPECT_NEAR(AngleBetweenDeg(Eigen::Quaterniond::Identity(), q), 1e-7, 1e-12);
}

TEST(RotationTest, FovFocalRoundTrip) {
  EXPECT_NEAR(FovDegFromFocalPx(FocalPxFromFovDeg(55, 1920), 1920), 55, 1e-12);
  EXPECT_NEAR(FocalPxFromFovDeg(90, 1000), 500, 1e-9);
}

}  // namespace
TEST(RotationTest, OpticalAxisAngleIgnoresRollAndCountsPanAndTilt) {
  PanTiltRoll roll_only, pan_tilt;
  roll_only.roll_deg = 40;
  pan_tilt.pan_deg = 3;
  pan_tilt.tilt_deg = 4;
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  EXPECT_NEAR(OpticalAxisAngleDeg(id, QuaternionFromPanTiltRoll(roll_only)), 0.0, 1e-6);
  // cos(angle) = cos(3 deg) cos(4 deg) for pan then tilt.
  const double expected = RadToDeg(std::acos(std::cos(DegToRad(3)) * std::cos(DegToRad(4))));
  EXPECT_NEAR(OpticalAxisAngleDeg(id, QuaternionFromPanTiltRoll(pan_tilt)), expected, 1e-9);
  EXPECT_NEAR(OpticalAxisAngleDeg(QuaternionFromPanTiltRoll(pan_tilt), id), expected, 1e-9);
  // Opposite axes: 180, no NaN from acos at the clamp.
  PanTiltRoll back;
  back.pan_deg = 180;
  EXPECT_NEAR(OpticalAxisAngleDeg(id, QuaternionFromPanTiltRoll(back)), 180.0, 1e-6);
}

}  // namespace hapcine
