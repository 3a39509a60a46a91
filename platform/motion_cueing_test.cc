#include "platform/motion_cueing.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "core/error.h"
#include "core/rotation.h"
#include "haptics/test_paths_for_test.h"
#include "platform/platform_safety.h"

namespace hapcine {
namespace {

using testing::MakeEffectPath;

constexpr int kSway = 0, kHeave = 1, kSurge = 2, kPitch = 3, kYaw = 4, kRoll = 5;

PlatformConfig Load(const char* name) {
  return LoadPlatformFile(std::string(HAPCINE_SOURCE_DIR) + "/haptics/" + name);
}
PlatformConfig Stewart() { return Load("platform_stewart.json"); }
PlatformConfig ThreeDof() { return Load("platform_3dof.json"); }

PlatformTrack Make(const CameraPath& path, const PlatformConfig& cfg) {
  PlatformOptions o;
  o.source = "test";
  return MakePlatformTrack(path, cfg, o);
}

// Largest and smallest value of one DOF over a track.
double Max(const PlatformTrack& t, int d) {
  double m = -1e9;
  for (const auto& s : t.samples) m = std::max(m, s.pose[d]);
  return m;
}
double Min(const PlatformTrack& t, int d) {
  double m = 1e9;
  for (const auto& s : t.samples) m = std::min(m, s.pose[d]);
  return m;
}
double Usable(const PlatformConfig& cfg, int d) {
  return cfg.cueing.usable_fraction * cfg.limits[d].position;
}

TEST(MotionCueing, Table1DirectionsOnASixDofStewart) {
  const PlatformConfig cfg = Stewart();
  const PlatformTrack crane = Make(MakeEffectPath(CameraEffect::kCraneShot), cfg);
  EXPECT_GT(Max(crane, kHeave), 0.8 * Usable(cfg, kHeave));  // crane up: heave up
  EXPECT_GT(-Min(crane, kHeave), -0.1 * Usable(cfg, kHeave));
  EXPECT_LT(Min(crane, kPitch), -DegToRad(1));                // its tilt down: pitch down
  const PlatformTrack dutch = Make(MakeEffectPath(CameraEffect::kDutchAngle), cfg);
  EXPECT_GT(Max(dutch, kRoll), 0.5 * Usable(cfg, kRoll));     // right side up, as Eq. 5
  EXPECT_LT(std::abs(Max(dutch, kHeave)) + std::abs(Min(dutch, kHeave)), 1e-6);
  const PlatformTrack travel = Make(MakeEffectPath(CameraEffect::kTraveling), cfg);
  EXPECT_GT(Max(travel, kSway), 0.8 * Usable(cfg, kSway));    // traveling right: sway right
  EXPECT_GT(Min(travel, kSway), -1e-3);
  const PlatformTrack left = Make(MakeEffectPath(CameraEffect::kTraveling, -1), cfg);
  EXPECT_LT(Min(left, kSway), -0.8 * Usable(cfg, kSway));     // and left: left
  const PlatformTrack tilt = Make(MakeEffectPath(CameraEffect::kTilting), cfg);
  EXPECT_GT(Max(tilt, kPitch), 0.5 * Usable(cfg, kPitch));    // tilting up: front up
  const PlatformTrack arc = Make(MakeEffectPath(CameraEffect::kArcing), cfg);
  EXPECT_GT(Max(arc, kYaw), 0.5 * Usable(cfg, kYaw));         // pan left while arcing
  EXPECT_GT(Max(arc, kSway), 0.5 * Usable(cfg, kSway));
  const PlatformTrack zoom = Make(MakeEffectPath(CameraEffect::kZoomIn), cfg);
  EXPECT_LT(Min(zoom, kSurge), -0.8 * Usable(cfg, kSurge));   // zoom-in: forward (-Z)
  const PlatformTrack vertigo = Make(MakeEffectPath(CameraEffect::kVertigo), cfg);
  EXPECT_LT(std::abs(Min(vertigo, kSurge)) + std::abs(Max(vertigo, kSurge)), 2e-3);  // cancels
}

TEST(MotionCueing, Table1DirectionsOnAThreeDofSeat) {
  const PlatformConfig cfg = ThreeDof();
  const PlatformTrack crane = Make(MakeEffectPath(CameraEffect::kCraneShot), cfg);
  EXPECT_GT(Max(crane, kHeave), 0.8 * Usable(cfg, kHeave));
  const PlatformTrack dutch = Make(MakeEffectPath(CameraEffect::kDutchAngle, -1), cfg);
  EXPECT_LT(Min(dutch, kRoll), -0.5 * Usable(cfg, kRoll));
  // No sway DOF: the traveling's start to the right is a tilt coordination
  // roll, right side up (gravity pushes the body left, as the acceleration would).
  const PlatformTrack travel = Make(MakeEffectPath(CameraEffect::kTraveling), cfg);
  double first = 0;
  for (const auto& s : travel.samples) {
    if (std::abs(s.pose[kRoll]) > DegToRad(0.2)) {
      first = s.pose[kRoll];
      break;
    }
  }
  EXPECT_GT(first, 0.0);
  for (const auto& s : travel.samples) EXPECT_EQ(s.pose[kSway], 0.0);
}

TEST(MotionCueing, ATwoDofPitchRollSeat) {
  const PlatformConfig cfg = ParsePlatformJson(
      R"({"type": "platform", "name": "2-DOF",
          "dofs": {"pitch": {"position": 10, "velocity": 20, "acceleration": 100},
                   "roll": {"position": 10, "velocity": 20, "acceleration": 100}}})",
      "2dof.json");
  const PlatformTrack tilt = Make(MakeEffectPath(CameraEffect::kTilting), cfg);
  EXPECT_GT(Max(tilt, kPitch), 0.5 * Usable(cfg, kPitch));
  const PlatformTrack dutch = Make(MakeEffectPath(CameraEffect::kDutchAngle), cfg);
  EXPECT_GT(Max(dutch, kRoll), 0.5 * Usable(cfg, kRoll));
  const PlatformTrack crane = Make(MakeEffectPath(CameraEffect::kCraneShot), cfg);
  EXPECT_LT(Min(crane, kPitch), -DegToRad(1));  // no heave: the crane's tilt down remains
  for (const auto& t : {tilt, dutch, crane}) {
    const PlatformLimitCheck c = MeasurePlatformLimits(t, cfg);
    EXPECT_EQ(c.disabled_max, 0.0);
    EXPECT_LE(c.acceleration_ratio, 1 + 1e-9);
  }
}

// While the camera signal of a DOF keeps its sign (the eased motion of a
// Table 1 clip, 1-6 s), the platform never moves against it; in the last
// still second it returns below the otoliths' threshold.
TEST(MotionCueing, NoFalseCuesAndSubThresholdReturns) {
  const PlatformConfig cfg = Stewart();
  const struct {
    CameraEffect effect;
    int dof;
    double sign;
    double tolerance;  // metres or radians
  } cases[] = {{CameraEffect::kTraveling, kSway, 1, 1e-3},
               {CameraEffect::kCraneShot, kHeave, 1, 1e-3},
               {CameraEffect::kZoomIn, kSurge, -1, 1e-3},
               {CameraEffect::kDutchAngle, kRoll, 1, DegToRad(0.05)},
               {CameraEffect::kTilting, kPitch, 1, DegToRad(0.05)}};
  for (const auto& c : cases) {
    testing::EffectPathSpec spec;
    spec.effect = c.effect;
    spec.motion_s = 20;  // a long move: the scaling alone would not keep it home
    const PlatformTrack t = Make(MakeEffectPath(spec), cfg);
    double best = -1e9, counter = 0;
    for (const auto& s : t.samples) {
      if (s.time_s < 1 || s.time_s > 21) continue;
      best = std::max(best, c.sign * s.pose[c.dof]);
      counter = std::max(counter, best - c.sign * s.pose[c.dof]);
    }
    EXPECT_LE(counter, c.tolerance) << static_cast<int>(c.effect);
    EXPECT_GT(best, 0.5 * Usable(cfg, c.dof)) << static_cast<int>(c.effect);
  }
  // The traveling's return in the still second after the move.
  const PlatformTrack t = Make(MakeEffectPath(CameraEffect::kTraveling), cfg);
  const double dt = 1 / t.rate_hz;
  for (size_t i = 2; i < t.samples.size(); ++i) {
    if (t.samples[i].time_s < 6.05) continue;
    const double a = (t.samples[i].pose[kSway] - 2 * t.samples[i - 1].pose[kSway] +
                      t.samples[i - 2].pose[kSway]) / (dt * dt);
    EXPECT_LE(std::abs(a), cfg.cueing.return_accel_m_s2 + 1e-6) << t.samples[i].time_s;
  }
  EXPECT_LT(t.samples.back().pose[kSway], Max(t, kSway));  // it does return
}

CameraPath AdversarialPath(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  CameraPath path;
  double t = 0;
  for (int i = 0; i < 600; ++i) {
    CameraFrame f;
    f.frame = i;
    // 1000 fps bursts of frame-to-frame 180 deg turns (~1e5-1e6 deg/s) and
    // 1e5-unit jumps, 30 fps stretches, single-frame shots, lost runs.
    t += i % 200 < 100 ? 1e-3 : 1.0 / 30;
    f.time_s = t;
    f.center = Eigen::Vector3d(u(rng), u(rng), u(rng)) * (i % 3 == 0 ? 1e5 : 1.0);
    f.world_from_cam = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    if (f.world_from_cam.w() < 0) f.world_from_cam.coeffs() *= -1;
    f.fov_deg = i % 2 ? 1.0 : 170.0;
    f.shot = i < 300 ? i / 50 : (i < 350 ? i : 400 + i / 60);  // i in [300, 350): one-frame shots
    if (i % 40 >= 30) {
      f.model = std::string(kLostModel);
      f.confidence = 0;
    }
    path.frames.push_back(f);
  }
  return path;
}

TEST(MotionCueing, LimitsHoldOnAdversarialCameraPaths) {
  for (const PlatformConfig& cfg : {Stewart(), ThreeDof()}) {
    for (uint64_t seed : {1, 2}) {
      const PlatformTrack t = Make(AdversarialPath(seed), cfg);
      const PlatformLimitCheck c = MeasurePlatformLimits(t, cfg);
      EXPECT_TRUE(c.finite);
      EXPECT_LE(c.position_ratio, 1 + 1e-9) << cfg.name;
      EXPECT_LE(c.velocity_ratio, 1 + 1e-9) << cfg.name;
      EXPECT_LE(c.acceleration_ratio, 1 + 1e-9) << cfg.name;
      EXPECT_TRUE(c.legs_in_stroke) << cfg.name;
      EXPECT_EQ(t.metadata.at("stroke_limited_samples"), "0") << cfg.name;
      EXPECT_NO_THROW(VerifyPlatformTrack(t, cfg));
      for (const auto& s : t.samples) {
        if (cfg.stewart) {
          ASSERT_TRUE(s.legs.has_value());
          EXPECT_TRUE(LegsWithinStroke(*cfg.stewart, *s.legs));
        }
      }
    }
  }
}

// A run of lost frames followed by a pose nothing measured (the estimator
// placed the camera 5 units away) is no motion: the platform stays home.
TEST(MotionCueing, LostFramesAreNotMotion) {
  CameraPath path;
  for (int i = 0; i < 150; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 30.0;
    f.fov_deg = 50;
    if (i >= 50 && i < 70) {
      f.model = std::string(kLostModel);
      f.confidence = 0;
    }
    if (i >= 70) f.center.x() = 5;
    path.frames.push_back(f);
  }
  const PlatformTrack t = Make(path, Stewart());
  EXPECT_LT(std::max(Max(t, kSway), -Min(t, kSway)), 1e-6);
  // The same jump without the lost frames is a (very fast) traveling right.
  for (auto& f : path.frames) f.model.reset();
  EXPECT_GT(Max(Make(path, Stewart()), kSway), 0.01);
}

TEST(MotionCueing, OneFramePathAndNoneModelStayHome) {
  CameraPath one;
  one.frames.resize(1);
  one.frames[0].fov_deg = 50;
  const PlatformTrack t = Make(one, Stewart());
  ASSERT_EQ(t.samples.size(), 1u);
  EXPECT_EQ(t.samples[0].pose, PlatformPose::Zero());
  PlatformOptions o;
  o.model = "none";
  const PlatformTrack none = MakePlatformTrack(MakeEffectPath(CameraEffect::kTraveling), Stewart(), o);
  EXPECT_EQ(Max(none, kSway), 0.0);
  o.model = "semantic";
  EXPECT_THROW(MakePlatformTrack(one, Stewart(), o), UsageError);
}

TEST(MotionCueing, CutsKeepThePoseContinuous) {
  // Two travelings back to back as two shots: the second restarts its
  // signal from zero; the pose must not jump at the cut.
  CameraPath a = MakeEffectPath(CameraEffect::kTraveling);
  const CameraPath b = MakeEffectPath(CameraEffect::kTraveling);
  const double offset = a.frames.back().time_s + 1.0 / 30;
  for (auto& f : a.frames) f.shot = 0;
  for (CameraFrame f : b.frames) {
    f.time_s += offset;
    f.shot = 1;
    a.frames.push_back(f);
  }
  const PlatformConfig cfg = Stewart();
  const PlatformTrack t = Make(a, cfg);
  const double max_step = cfg.limits[kSway].velocity / t.rate_hz;
  for (size_t i = 1; i < t.samples.size(); ++i) {
    EXPECT_LE(std::abs(t.samples[i].pose[kSway] - t.samples[i - 1].pose[kSway]), max_step + 1e-12);
  }
  EXPECT_EQ(t.metadata.at("stroke_limited_samples"), "0");
}

TEST(PlatformTrack, CsvRoundTrip) {
  const PlatformConfig cfg = Stewart();
  const PlatformTrack t = Make(MakeEffectPath(CameraEffect::kArcing), cfg);
  std::stringstream ss;
  WritePlatformTrack(t, ss);
  const PlatformTrack back = ReadPlatformTrack(ss, "rt.platform.csv");
  ASSERT_EQ(back.samples.size(), t.samples.size());
  EXPECT_EQ(back.platform, cfg.name);
  EXPECT_EQ(back.dofs, "sway heave surge pitch yaw roll");
  EXPECT_EQ(back.metadata.at("clamped_samples"), t.metadata.at("clamped_samples"));
  for (size_t i = 0; i < t.samples.size(); i += 37) {
    EXPECT_NEAR(back.samples[i].time_s, t.samples[i].time_s, 1e-6);
    for (int d = 0; d < kNumDofs; ++d) EXPECT_NEAR(back.samples[i].pose[d], t.samples[i].pose[d], 1e-7);
    ASSERT_TRUE(back.samples[i].legs.has_value());
    EXPECT_NEAR((*back.samples[i].legs)[3], (*t.samples[i].legs)[3], 1e-7);
  }
  std::stringstream bad("# type=platform\n# rate_hz=100\n# model=x\n# source=s\n"
                        "time_s,x_m,y_m,z_m,pitch_deg,yaw_deg,roll_deg\n0,0,0,0,0,0,nan\n");
  EXPECT_THROW(ReadPlatformTrack(bad, "bad.csv"), Error);
}

}  // namespace
}  // namespace hapcine
