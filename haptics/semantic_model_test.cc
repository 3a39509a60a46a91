#include "haptics/semantic_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

constexpr int H = 0, L = 1, R = 2;

std::vector<double> Times(double t1, double rate = 1000) {
  std::vector<double> t;
  for (size_t i = 0; i / rate <= t1 + 1e-12; ++i) t.push_back(i / rate);
  return t;
}

std::vector<ActuatorFrame> Model(CameraEffect e, double intensity = 1.0) {
  return SemanticFrames(Times(8.0), {{1.0, 6.0, e, intensity}}, SeatGeometry(), SemanticOptions());
}

size_t At(double t) { return static_cast<size_t>(std::lround(t * 1000)); }

double MaxCoord(const std::vector<ActuatorFrame>& v) {
  double m = 0;
  for (const auto& f : v)
    for (const auto& a : f) m = std::max(m, a.cwiseAbs().maxCoeff());
  return m;
}

TEST(SemanticModel, NamesBothTables) {
  EXPECT_EQ(EffectFromName("crab_walk"), CameraEffect::kTraveling);
  EXPECT_EQ(EffectFromName("traveling"), CameraEffect::kTraveling);
  EXPECT_EQ(EffectFromName("flying_away"), CameraEffect::kCraneShot);
  EXPECT_FALSE(EffectFromName("dolly").has_value());
  EXPECT_STREQ(MetaphorName(CameraEffect::kDutchAngle), "instability");
  for (int e = 0; e < kNumCameraEffects; ++e) {
    EXPECT_EQ(EffectFromName(EffectName(static_cast<CameraEffect>(e))),
              static_cast<CameraEffect>(e));
  }
}

TEST(SemanticModel, EveryPatternStaysInRangeAndStartsAndEndsCentred) {
  const SeatGeometry seat;
  for (int e = 1; e < kNumCameraEffects; ++e) {
    const auto v = Model(static_cast<CameraEffect>(e));
    EXPECT_LE(MaxCoord(v), seat.usable_half_m + 1e-12);
    EXPECT_GT(MaxCoord(v), 0.5 * seat.usable_half_m) << e;
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_EQ(v[At(0.5)][a], Eigen::Vector3d::Zero());
      EXPECT_LT(v[At(7.5)][a].norm(), 1e-12) << e;  // released within 1 s
    }
    double max_step = 0;
    for (size_t i = 1; i < v.size(); ++i) {
      for (int a = 0; a < kNumActuators; ++a) {
        max_step = std::max(max_step, (v[i][a] - v[i - 1][a]).cwiseAbs().maxCoeff());
      }
    }
    EXPECT_LT(max_step, 0.5 / 1000) << e;  // no jumps: < 0.5 m/s
  }
}

TEST(SemanticModel, FlyingAwayGoesUpAndDownWithIncreasingIntensity) {
  const auto v = Model(CameraEffect::kCraneShot);
  double early = 0, late = 0;
  for (size_t i = At(1.0); i < At(2.0); ++i) early = std::max(early, std::abs(v[i][H].y()));
  for (size_t i = At(5.0); i < At(6.0); ++i) late = std::max(late, std::abs(v[i][H].y()));
  EXPECT_GT(late, 2 * early);
  EXPECT_GT(v[At(5.25)][L].y(), 0.02);   // up...
  EXPECT_LT(v[At(5.75)][L].y(), -0.02);  // ...then down
}

TEST(SemanticModel, InstabilityAlternatesTheHands) {
  const auto v = Model(CameraEffect::kDutchAngle);
  EXPECT_GT(v[At(1.25)][L].y(), 0.02);
  EXPECT_NEAR(v[At(1.25)][R].y(), -v[At(1.25)][L].y(), 1e-12);
  EXPECT_LT(v[At(1.75)][L].y(), -0.02);
}

TEST(SemanticModel, LinearPatternsTowardsAwayAndDown) {
  const SeatGeometry seat;
  const auto arc = Model(CameraEffect::kArcing);
  const auto vert = Model(CameraEffect::kVertigo);
  const auto tilt = Model(CameraEffect::kTilting);
  for (int a = 0; a < kNumActuators; ++a) {
    const Eigen::Vector3d out = seat.FromCenter(a).normalized();
    EXPECT_LT(arc[At(6.0)][a].dot(out), -0.02);  // towards G
    EXPECT_GT(vert[At(6.0)][a].dot(out), 0.02);  // away from G
    EXPECT_NEAR(tilt[At(6.0)][a].y(), -seat.usable_half_m, 1e-12);
    // Linear: halfway in time, halfway in space.
    EXPECT_NEAR(tilt[At(3.5)][a].y(), -seat.usable_half_m / 2, 1e-12);
  }
}

TEST(SemanticModel, CrabWalkAlternatesAndFollowsTheDirection) {
  const auto v = Model(CameraEffect::kTraveling);  // 1 -> 6 s: 10 half-steps of 0.5 s
  // The paper's timing (Table 2): the right hand moves right alone first...
  EXPECT_GT(v[At(1.25)][R].x(), 0.02);
  EXPECT_NEAR(v[At(1.25)][L].x(), 0, 1e-12);
  // ... then it goes back while the left one moves right, and so on.
  for (double t = 1.55; t < 5.45; t += 0.05) {
    const double dr = v[At(t + 0.01)][R].x() - v[At(t - 0.01)][R].x();
    const double dl = v[At(t + 0.01)][L].x() - v[At(t - 0.01)][L].x();
    const bool turning = std::abs(std::remainder(t - 1.0, 0.5)) < 0.03;  // a hand at rest or at its peak
    if (!turning) {
      EXPECT_LT(dr * dl, 0) << t;  // one returns while the other steps
    }
  }
  EXPECT_GT(v[At(1.75)][L].x(), 0.02);
  EXPECT_GT(v[At(1.75)][R].x(), 0.02);  // both out, passing each other
  EXPECT_NEAR(v[At(5.75)][L].x(), 0, 1e-12);  // the last half-step: the right returns alone
  EXPECT_GT(v[At(5.75)][R].x(), 0.02);
  for (int a = 0; a < kNumActuators; ++a) EXPECT_NEAR(v[At(6.0)][a].norm(), 0, 1e-12);
  const auto left = Model(CameraEffect::kTraveling, -1);
  EXPECT_LT(left[At(1.25)][L].x(), -0.02);  // mirrored: left hand leads, to the left
  const auto fwd = Model(CameraEffect::kZoomIn);
  EXPECT_LT(fwd[At(1.25)][R].z(), -0.02);  // walk forward = -Z
  EXPECT_NEAR(fwd[At(1.25)][R].x(), 0, 1e-12);
}

TEST(SemanticModel, IntensityScalesAndEffectLabels) {
  std::vector<CameraEffect> labels;
  const auto half = SemanticFrames(Times(8.0), {{1.0, 6.0, CameraEffect::kTilting, 0.5}},
                                   SeatGeometry(), SemanticOptions(), &labels);
  EXPECT_NEAR(half[At(6.0)][0].y(), -0.5 * SeatGeometry().usable_half_m, 1e-12);
  EXPECT_EQ(labels[At(0.5)], CameraEffect::kNone);
  EXPECT_EQ(labels[At(3.0)], CameraEffect::kTilting);
  EXPECT_EQ(labels[At(7.0)], CameraEffect::kNone);
}

TEST(SemanticModel, RejectsBadSegments) {
  const SeatGeometry seat;
  const SemanticOptions o;
  const auto t = Times(2.0);
  EXPECT_ANY_THROW(SemanticFrames(t, {{1.0, 0.5, CameraEffect::kTilting, 1}}, seat, o));
  EXPECT_ANY_THROW(SemanticFrames(t, {{0, 1, CameraEffect::kTilting, 1.5}}, seat, o));
  EXPECT_ANY_THROW(SemanticFrames(
      t, {{0, 1, CameraEffect::kTilting, 1}, {0.5, 1.5, CameraEffect::kVertigo, 1}}, seat, o));
}

}  // namespace
}  // namespace hapcine
