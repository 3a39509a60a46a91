// The haptic models on the exact ground truth of `hapcine synth` (the paper's
// seven Table 1 clips and the hard cases), with default options: the tests
// the issue names (section 4.3's expected behaviour of the cinematic model),
// the classifier's labels on every preset, and a multi-shot film made of the
// seven clips back to back.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include "datasets/synth_clip.h"
#include "haptics/effect_classifier.h"
#include "haptics/false_cues.h"
#include "haptics/haptic_models.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

constexpr int H = 0, L = 1, R = 2;

CameraPath GroundTruth(const std::string& preset) {
  return SynthGroundTruth(preset, SynthOptions{});
}

HapticTrack Cinematic(const CameraPath& path, WashoutMode washout = WashoutMode::kAdaptive) {
  HapticOptions o;
  o.source = "synth";
  o.washout.mode = washout;
  return MakeHapticTrack(path, o);
}

// Every washout mode: the properties below hold whichever is chosen.
constexpr WashoutMode kWashoutModes[] = {WashoutMode::kAdaptive, WashoutMode::kHighPass,
                                         WashoutMode::kOff};

double MaxAbs(const HapticTrack& t, int actuator, int axis) {
  double m = 0;
  for (const auto& s : t.samples) m = std::max(m, std::abs(s.pos_m[actuator][axis]));
  return m;
}

using testing::MaxCoord;
using testing::MaxStep;

// The sample at time t (1 kHz track starting at 0).
const HapticSample& At(const HapticTrack& t, double time_s) {
  return t.samples[static_cast<size_t>(std::lround(time_s * t.rate_hz))];
}

TEST(SynthHaptics, VertigoGivesNoMovement) {
  // The paper: the forward movement and the zoom-out (a backward movement by
  // Equation 6) cancel. The ground truth carries no subject distance: the
  // model finds the dolly zoom's own (7 m) from the motion.
  for (const char* preset : {"vertigo", "dolly_zoom_parallax"}) {
    for (WashoutMode washout : kWashoutModes) {
      const HapticTrack t = Cinematic(GroundTruth(preset), washout);
      // 100 nm: the FOVs are floats (~1e-7 of their value).
      EXPECT_LT(MaxCoord(t), 1e-7) << preset << " washout " << WashoutModeName(washout);
    }
  }
  const auto shots = SplitShots(GroundTruth("vertigo"));
  const auto d = DollyZoomSubjectDistance(GroundTruth("vertigo"), shots[0]);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, 7.0, 0.05);  // "forward 7 -> 3 m from the characters"
}

TEST(SynthHaptics, ZoomInGivesForwardMovement) {
  const HapticTrack t = Cinematic(GroundTruth("zoom_in"), WashoutMode::kOff);
  const HapticSample& end = At(t, 6.5);
  for (int a = 0; a < kNumActuators; ++a) {
    EXPECT_LT(end.pos_m[a].z(), -0.04) << a;  // forward = -Z, nearly the whole range
    EXPECT_LT(MaxAbs(t, a, 0), 1e-9);
    EXPECT_LT(MaxAbs(t, a, 1), 1e-9);
  }
  // With the high-pass washout the onset is the same forward movement, then
  // it returns (while the zoom goes on: the false cue the default avoids).
  const HapticTrack w = Cinematic(GroundTruth("zoom_in"), WashoutMode::kHighPass);
  for (int a = 0; a < kNumActuators; ++a) {
    EXPECT_LT(At(w, 3.5).pos_m[a].z(), -0.02) << a;
    // The scaling fills the usable range (a 100 Hz row lands within microns of the peak).
    EXPECT_NEAR(MaxAbs(w, a, 2), 0.045, 1e-5) << a;
  }
}

TEST(SynthHaptics, DutchAngleMovesLeftHandDownAndRightHandUp) {
  for (WashoutMode washout : kWashoutModes) {
    const HapticTrack t = Cinematic(GroundTruth("dutch_angle"), washout);
    const HapticSample& s = At(t, 4.0);
    EXPECT_LT(s.pos_m[L].y(), -0.01) << WashoutModeName(washout);
    EXPECT_GT(s.pos_m[R].y(), 0.01) << WashoutModeName(washout);
    // A rotation about the chest, in the X-Y plane (about Z): every actuator
    // keeps its distance to G, nothing moves forward or backward.
    const SeatGeometry seat;
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_NEAR((seat.FromCenter(a) + s.pos_m[a]).norm(), seat.FromCenter(a).norm(), 5e-6);
      EXPECT_NEAR(s.pos_m[a].z(), 0, 1e-12);
    }
    EXPECT_LT(s.pos_m[H].x(), -0.005);  // the head leans to the left
  }
}

TEST(SynthHaptics, TravelingMovesAllThreeSidewaysTogether) {
  const HapticTrack t = Cinematic(GroundTruth("traveling"), WashoutMode::kOff);
  // The camera moves x -2 -> +2 m: everyone goes right by the same amount.
  EXPECT_NEAR(At(t, 6.5).pos_m[H].x(), 0.045, 1e-6);
  for (const auto& s : t.samples) {
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_NEAR(s.pos_m[a].x(), s.pos_m[H].x(), 1e-12);
      EXPECT_NEAR(s.pos_m[a].y(), 0, 1e-9);
      EXPECT_NEAR(s.pos_m[a].z(), 0, 1e-9);
    }
  }
  const HapticTrack w = Cinematic(GroundTruth("traveling"));
  EXPECT_GT(At(w, 3.5).pos_m[H].x(), 0.02);
  for (const auto& s : w.samples)
    for (int a = 0; a < kNumActuators; ++a) EXPECT_NEAR(s.pos_m[a].x(), s.pos_m[H].x(), 1e-12);
}

TEST(SynthHaptics, TiltingRotatesAboutTheChest) {
  const SeatGeometry seat;
  for (WashoutMode washout : kWashoutModes) {
    const HapticTrack t = Cinematic(GroundTruth("tilting"), washout);
    EXPECT_GT(MaxCoord(t), 0.04);
    for (const auto& s : t.samples) {
      for (int a = 0; a < kNumActuators; ++a) {
        // Every actuator keeps its distance to G and moves in the Y-Z plane.
        const Eigen::Vector3d ga = seat.FromCenter(a);
        // (to within the sagitta of the linear interpolation between frames)
        EXPECT_NEAR((ga + s.pos_m[a]).norm(), ga.norm(), 5e-6);
        EXPECT_NEAR(s.pos_m[a].x(), 0, 1e-12);
      }
    }
    // Tilting up (-18 -> +14 deg): the head goes backward, the hands (in
    // front of and below the chest) go up.
    const HapticSample& s = At(t, 4.0);
    EXPECT_GT(s.pos_m[H].z(), 0.005) << WashoutModeName(washout);
    EXPECT_GT(s.pos_m[L].y(), 0.005) << WashoutModeName(washout);
  }
}

TEST(SynthHaptics, CraneShotLiftsEveryone) {
  const HapticTrack t = Cinematic(GroundTruth("crane_shot"), WashoutMode::kOff);
  for (int a = 0; a < kNumActuators; ++a) EXPECT_GT(At(t, 6.5).pos_m[a].y(), 0.01) << a;
}

// The pre-processing pass uses the workspace: every Table 1 clip that moves
// the actuators reaches the usable range (45 mm) to within 1 mm, also when
// T and R point different ways (crane: up + tilt down; arcing: sideways +
// pan), with and without washout.
TEST(SynthHaptics, ScalingUsesTheWholeUsableRange) {
  for (const std::string& preset : SynthTable1PresetNames()) {
    if (preset == "vertigo") continue;
    for (WashoutMode washout : kWashoutModes) {
      const double peak = MaxCoord(Cinematic(GroundTruth(preset), washout));
      EXPECT_GT(peak, 0.044) << preset << " washout " << WashoutModeName(washout);
      EXPECT_LE(peak, 0.045 + 1e-12) << preset;
    }
  }
}

// The default washout gives no false cue and, on the seven Table 1 clips,
// is exactly the paper's Equations 2-6 with the per-shot scaling; the
// high-pass washout moves 10-25 mm back while the camera still moves.
TEST(SynthHaptics, DefaultIsEquations2To6WithNoFalseCue) {
  for (const std::string& preset : SynthTable1PresetNames()) {
    const CameraPath path = GroundTruth(preset);
    const HapticTrack def = Cinematic(path), off = Cinematic(path, WashoutMode::kOff);
    ASSERT_EQ(def.samples.size(), off.samples.size());
    for (size_t i = 0; i < def.samples.size(); ++i) {
      for (int a = 0; a < kNumActuators; ++a) {
        ASSERT_EQ(def.samples[i].pos_m[a], off.samples[i].pos_m[a]) << preset << " " << i;
      }
    }
    const SeatGeometry seat;
    const auto cues = MeasureFalseCues(path, def, seat, CinematicOptions{});
    ASSERT_EQ(cues.size(), 1u);
    EXPECT_LT(cues[0].counter_m, 1e-3) << preset;
    if (preset == "vertigo") continue;  // nothing moves
    const HapticTrack hp = Cinematic(path, WashoutMode::kHighPass);
    EXPECT_GT(MeasureFalseCues(path, hp, seat, CinematicOptions{})[0].counter_m, 0.009) << preset;
  }
}

// Joint scaling must not amplify an imperfect Vertigo cancellation back to
// a large movement: with D 5 % off (7.35 m instead of 7) the residual stays
// a few millimetres.
TEST(SynthHaptics, NearlyCancellingDollyZoomStaysSmall) {
  HapticOptions o;
  o.cinematic.reference_depth_u = 7.35;
  EXPECT_LT(MaxCoord(MakeHapticTrack(GroundTruth("vertigo"), o)), 0.003);
}

TEST(SynthHaptics, EveryPresetAndModelStaysInTheWorkspace) {
  for (const std::string& preset : SynthPresetNames()) {
    for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic, HapticModel::kRandom,
                          HapticModel::kNone}) {
      HapticOptions o;
      o.model = m;
      const HapticTrack t = MakeHapticTrack(GroundTruth(preset), o);
      EXPECT_LE(MaxCoord(t), o.seat.usable_half_m + 1e-12) << preset << " " << t.model;
      EXPECT_LE(MaxStep(t), o.washout.max_speed_m_s / o.OutputRateHz() + 1e-15)
          << preset << " " << t.model;
      EXPECT_EQ(t.metadata.at("clamped_samples"), "0") << preset << " " << t.model;
    }
  }
}

// The label each preset should get (docs/haptics.md: a pan is labelled
// traveling, following something sideways; directions go into the sign of
// the intensity: the pans turn left (positive pan), so they travel left, and
// hard_cut's second camera trucks left).
const std::map<std::string, std::vector<std::pair<CameraEffect, double>>>& ExpectedLabels() {
  using E = CameraEffect;
  static const std::map<std::string, std::vector<std::pair<E, double>>> k = {
      {"crane_shot", {{E::kCraneShot, 1}}},
      {"dutch_angle", {{E::kDutchAngle, 1}}},
      {"arcing", {{E::kArcing, 1}}},
      {"traveling", {{E::kTraveling, 1}}},
      {"tilting", {{E::kTilting, 1}}},
      {"zoom_in", {{E::kZoomIn, 1}}},
      {"vertigo", {{E::kVertigo, 1}}},
      {"slow_pan", {{E::kTraveling, -1}}},
      {"whip_pan", {{E::kTraveling, -1}}},
      {"handheld_shake", {}},
      {"telephoto_zoom_pan", {{E::kZoomIn, 1}}},
      {"dolly_zoom_parallax", {{E::kVertigo, 1}}},
      {"low_texture", {{E::kTraveling, -1}}},
      {"noise_compression", {{E::kTraveling, 1}}},
      {"hard_cut", {{E::kTraveling, -1}, {E::kTraveling, -1}}},
      {"fade_to_black", {{E::kTraveling, -1}}},
      {"static_camera", {}},
  };
  return k;
}

TEST(SynthHaptics, ClassifierLabelsEveryPreset) {
  int right = 0, total = 0;
  for (const std::string& preset : SynthPresetNames()) {
    ASSERT_TRUE(ExpectedLabels().count(preset)) << preset;
    const auto& expected = ExpectedLabels().at(preset);
    const auto segs = ClassifyEffects(GroundTruth(preset), ClassifierOptions{});
    bool ok = segs.size() == expected.size();
    for (size_t i = 0; ok && i < segs.size(); ++i) {
      ok = segs[i].effect == expected[i].first && segs[i].intensity * expected[i].second > 0;
    }
    EXPECT_TRUE(ok) << preset << ": " << segs.size() << " segments, first "
                    << (segs.empty() ? "-" : EffectName(segs[0].effect));
    right += ok;
    ++total;
  }
  std::cout << "[ classifier on synth ground truth ] " << right << "/" << total << " presets\n";
  // The Table 1 clips: one segment covering the 5 s move (1 s -> 6 s).
  for (const std::string& preset : SynthTable1PresetNames()) {
    const auto segs = ClassifyEffects(GroundTruth(preset), ClassifierOptions{});
    ASSERT_EQ(segs.size(), 1u) << preset;
    EXPECT_NEAR(segs[0].start_s, 1.0, 0.5) << preset;
    EXPECT_NEAR(segs[0].end_s, 6.0, 0.5) << preset;
  }
}

// The seven Table 1 clips back to back as one 49 s film, one shot each: the
// camera jumps at every cut (different positions, angles, FOV).
CameraPath SevenShotFilm() {
  CameraPath film;
  int frame = 0, shot = 0;
  double t0 = 0;
  for (const std::string& preset : SynthTable1PresetNames()) {
    const CameraPath clip = GroundTruth(preset);
    for (CameraFrame f : clip.frames) {
      f.frame = frame++;
      f.time_s += t0;
      f.shot = shot;
      film.frames.push_back(f);
    }
    t0 = film.frames.back().time_s + (clip.frames[1].time_s - clip.frames[0].time_s);
    ++shot;
  }
  return film;
}

TEST(SynthHaptics, MultiShotFilmStaysInTheWorkspaceAndNeverJumpsAtACut) {
  for (const bool hard_cut_clip : {true, false}) {
    const CameraPath film = hard_cut_clip ? GroundTruth("hard_cut") : SevenShotFilm();
    for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic}) {
      HapticOptions o;
      o.model = m;
      const HapticTrack t = MakeHapticTrack(film, o);
      const double bound = o.washout.max_speed_m_s / o.OutputRateHz();
      EXPECT_LE(MaxCoord(t), o.seat.usable_half_m + 1e-12);
      EXPECT_LE(MaxStep(t), bound + 1e-15);
      EXPECT_EQ(t.metadata.at("clamped_samples"), "0");
      // The crossfade, not the speed limit, is what keeps the cuts smooth.
      EXPECT_EQ(t.metadata.at("rate_limited_samples"), "0") << t.model;
      std::cout << "[ " << (hard_cut_clip ? "hard_cut" : "seven-shot film") << " " << t.model
                << " ] max |coord| " << MaxCoord(t) << " m, max step " << MaxStep(t) * 1e3
                << " mm per ms\n";
    }
  }
  // One scaling for the whole film (the smallest factors, then the gain
  // every shot allows): still inside, never clamped.
  HapticOptions film_scaling;
  film_scaling.cinematic.per_film_scaling = true;
  for (const CameraPath& film : {SevenShotFilm(), GroundTruth("hard_cut")}) {
    const HapticTrack t = MakeHapticTrack(film, film_scaling);
    EXPECT_LE(MaxCoord(t), film_scaling.seat.usable_half_m + 1e-12);
    EXPECT_GT(MaxCoord(t), 0.01);
    EXPECT_EQ(t.metadata.at("clamped_samples"), "0");
  }
  // Without the crossfade the seven-shot film would jump at its cuts (the
  // speed limit would then have to catch it): the crossfade is doing work.
  HapticOptions o;
  o.washout.cut_ramp_s = 0;
  o.washout.mode = WashoutMode::kOff;
  EXPECT_NE(MakeHapticTrack(SevenShotFilm(), o).metadata.at("rate_limited_samples"), "0");
}

}  // namespace
}  // namespace hapcine
