#include "haptics/false_cues.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "haptics/haptic_models.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using testing::MakeEffectPath;
using testing::MaxCoord;

// A sideways path at 25 fps, one shot per entry of `shot_lengths_s`, whose
// camera x at time t (from the shot start) is x_of_t(t).
CameraPath SidewaysPath(const std::vector<double>& shot_lengths_s,
                        const std::function<double(double)>& x_of_t) {
  CameraPath path;
  double t0 = 0;
  int frame = 0;
  for (size_t k = 0; k < shot_lengths_s.size(); ++k) {
    const int n = std::max(1, static_cast<int>(std::lround(shot_lengths_s[k] * 25)));
    for (int i = 0; i < n; ++i) {
      CameraFrame f;
      f.frame = frame++;
      f.time_s = t0 + i / 25.0;
      f.center = Eigen::Vector3d(x_of_t(i / 25.0), 0, 0);
      f.fov_deg = 50;
      f.shot = static_cast<int>(k);
      path.frames.push_back(f);
    }
    t0 += n / 25.0;
  }
  return path;
}

HapticTrack Track(const CameraPath& path, WashoutMode mode = WashoutMode::kAdaptive) {
  HapticOptions o;
  o.rate_hz = 100;
  o.washout.mode = mode;
  return MakeHapticTrack(path, o);
}

double WorstCounterMotion(const CameraPath& path, const HapticTrack& track) {
  double worst = 0;
  for (const ShotFalseCue& c : MeasureFalseCues(path, track, SeatGeometry{}, CinematicOptions{})) {
    worst = std::max(worst, c.counter_m);
  }
  return worst;
}

void ExpectFiniteAndInside(const HapticTrack& t) {
  for (const HapticSample& s : t.samples) {
    for (const auto& p : s.pos_m) ASSERT_TRUE(p.allFinite()) << s.time_s;
  }
  EXPECT_LE(MaxCoord(t), SeatGeometry{}.usable_half_m + 1e-12);
  EXPECT_EQ(t.metadata.at("clamped_samples"), "0");
}

// The measure can fail: the high-pass washout moves back during the move.
TEST(FalseCues, HighPassWashoutMovesBackWhileTheCameraKeepsMoving) {
  for (CameraEffect e : {CameraEffect::kTraveling, CameraEffect::kZoomIn, CameraEffect::kDutchAngle}) {
    const CameraPath path = MakeEffectPath(e);
    EXPECT_GT(WorstCounterMotion(path, Track(path, WashoutMode::kHighPass)), 0.005) << int(e);
    EXPECT_LT(WorstCounterMotion(path, Track(path)), 1e-3) << int(e);
  }
}

// A short shot's default track is the plain Equations 2-6 with the per-shot
// scaling: the adaptive washout leaves it alone.
TEST(FalseCues, ShortShotsGetNoWashout) {
  for (CameraEffect e : {CameraEffect::kTraveling, CameraEffect::kCraneShot, CameraEffect::kArcing,
                         CameraEffect::kTilting}) {
    const CameraPath path = MakeEffectPath(e);
    const HapticTrack a = Track(path), off = Track(path, WashoutMode::kOff);
    ASSERT_EQ(a.samples.size(), off.samples.size());
    for (size_t i = 0; i < a.samples.size(); ++i) {
      for (int k = 0; k < kNumActuators; ++k) {
        ASSERT_EQ(a.samples[i].pos_m[k], off.samples[i].pos_m[k]) << int(e) << " " << i;
      }
    }
    EXPECT_EQ(a.metadata.at("return_tau_s"), "0");
  }
}

// A two-minute drift whose speed swings between 0.1 and 0.9 units/s (it
// slows down every 15 s but never stops): felt much sooner than with scaling
// alone, never moving back while the camera goes on, inside the workspace.
TEST(FalseCues, TwoMinuteDriftHoldsInsteadOfMovingBack) {
  const CameraPath path = SidewaysPath({120}, [](double t) {
    return 0.5 * t - 0.4 * 15 / (2 * M_PI) * std::cos(2 * M_PI * t / 15);
  });
  const HapticTrack t = Track(path), off = Track(path, WashoutMode::kOff);
  ExpectFiniteAndInside(t);
  EXPECT_LT(WorstCounterMotion(path, t), 1e-3);
  EXPECT_GT(WorstCounterMotion(path, Track(path, WashoutMode::kHighPass)), 0.01);
  // 10 s in: scaling alone has moved 45 mm / 12; the adaptive track more than twice that.
  EXPECT_GT(t.samples[1000].pos_m[0].x(), 2 * off.samples[1000].pos_m[0].x());
  EXPECT_GT(std::stod(t.metadata.at("return_tau_s")), 0);
}

// Right for 30 s, then left for 30 s, then still: the sign flip is followed
// at once, the return happens only in the still part, with an acceleration
// of at most return_accel_m_s2.
TEST(FalseCues, SignFlipAndReturnInTheStillPart) {
  const CameraPath path = SidewaysPath({80}, [](double t) {
    return t < 30 ? 0.4 * t : t < 60 ? 12 - 0.4 * (t - 30) - 0.1 * (t - 30) : -3.0;
  });
  const HapticTrack t = Track(path);
  ExpectFiniteAndInside(t);
  EXPECT_LT(WorstCounterMotion(path, t), 1e-3);
  // Back near the centre by the end of the 20 s still part.
  EXPECT_LT(std::abs(t.samples.back().pos_m[0].x()), 0.005);
  // The return's acceleration, from 0.1 s differences in the still part.
  const double a_max = WashoutOptions{}.return_accel_m_s2;
  for (size_t i = 6100; i + 20 < t.samples.size(); i += 10) {
    const double x0 = t.samples[i].pos_m[0].x(), x1 = t.samples[i + 10].pos_m[0].x(),
                 x2 = t.samples[i + 20].pos_m[0].x();
    EXPECT_LE(std::abs(x2 - 2 * x1 + x0) / (0.1 * 0.1), a_max * 1.01) << i;
  }
}

// A one-frame shot between two long drifts, and a path of one frame: no NaN,
// nothing outside the workspace, no counter-motion.
TEST(FalseCues, SingleFrameShotsAreFinite) {
  const CameraPath path = SidewaysPath({60, 0.04, 60}, [](double t) { return 0.3 * t; });
  const HapticTrack t = Track(path);
  ExpectFiniteAndInside(t);
  EXPECT_LT(WorstCounterMotion(path, t), 1e-3);
  const auto cues = MeasureFalseCues(path, t, SeatGeometry{}, CinematicOptions{});
  ASSERT_EQ(cues.size(), 3u);
  EXPECT_EQ(cues[1].counter_m, 0);
  const CameraPath one = SidewaysPath({0.04}, [](double) { return 1.0; });
  ExpectFiniteAndInside(Track(one));
}

// The measure itself: a made-up track that goes back 20 mm over 0.5 s in the
// middle of a traveling, and returns 40 mm after the camera has stopped.
TEST(FalseCues, MeasureFindsTheRetreatAndIgnoresStillReturns) {
  const CameraPath path = MakeEffectPath(CameraEffect::kTraveling);  // moves 1 -> 6 s
  HapticTrack t = Track(path, WashoutMode::kOff);
  for (HapticSample& s : t.samples) {
    double dip = 0;
    if (s.time_s > 3.0 && s.time_s < 3.5) dip = 0.04 * (s.time_s - 3.0);
    if (s.time_s >= 3.5 && s.time_s < 4.0) dip = 0.02 - 0.04 * (s.time_s - 3.5);
    if (s.time_s > 6.0) dip = std::min(0.04, 0.04 * (s.time_s - 6.0));
    for (auto& p : s.pos_m) p.x() -= (p.x() > 0 ? 1 : -1) * dip;
  }
  const auto cues = MeasureFalseCues(path, t, SeatGeometry{}, CinematicOptions{});
  ASSERT_EQ(cues.size(), 1u);
  // The dip minus the forward motion meanwhile (the traveling goes on).
  EXPECT_GT(cues[0].counter_m, 0.008);
  EXPECT_LT(cues[0].counter_m, 0.020);
  EXPECT_NEAR(cues[0].at_s, 3.0, 0.2);
  EXPECT_GT(cues[0].duration_s, 0.05);
  EXPECT_LT(cues[0].duration_s, 0.6);
}

}  // namespace
}  // namespace hapcine
