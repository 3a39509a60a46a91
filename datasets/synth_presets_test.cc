#include "datasets/synth_presets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/camera_path.h"
#include "core/error.h"
#include "core/rotation.h"
#include "datasets/render.h"
#include "datasets/synth_clip.h"

namespace hapcine {
namespace {

using Eigen::Vector3d;

SynthOptions Opts() {
  SynthOptions o;  // the paper's 7 s at 24 fps, 1280x720
  return o;
}

struct Params {
  double x, y, z, pan, tilt, roll, fov;
};

Params P(const CameraFrame& f) {
  const PanTiltRoll a = PanTiltRollFromQuaternion(f.world_from_cam);
  return {f.center.x(), f.center.y(), f.center.z(), a.pan_deg, a.tilt_deg, a.roll_deg, f.fov_deg};
}

std::vector<double> AsVec(const Params& p) { return {p.x, p.y, p.z, p.pan, p.tilt, p.roll, p.fov}; }

// Which of the 7 paper parameters change anywhere in the clip.
std::vector<bool> Changed(const CameraPath& path) {
  std::vector<bool> out(7, false);
  const auto first = AsVec(P(path.frames.front()));
  for (const auto& f : path.frames) {
    const auto v = AsVec(P(f));
    for (int k = 0; k < 7; ++k) out[k] = out[k] || std::abs(v[k] - first[k]) > 1e-9;
  }
  return out;
}

void ExpectStillEnds(const CameraPath& path) {
  // Still for the first and the last second (24 frames each at 24 fps).
  const int n = static_cast<int>(path.frames.size());
  ASSERT_EQ(n, 168);
  for (int i = 0; i <= 24; ++i) {
    EXPECT_EQ(path.frames[i].center, path.frames[0].center) << i;
    EXPECT_EQ(path.frames[i].world_from_cam.coeffs(), path.frames[0].world_from_cam.coeffs());
    EXPECT_EQ(path.frames[i].fov_deg, path.frames[0].fov_deg);
  }
  for (int i = 144; i < n; ++i) {
    EXPECT_EQ(path.frames[i].center, path.frames[n - 1].center) << i;
    EXPECT_EQ(path.frames[i].world_from_cam.coeffs(), path.frames[n - 1].world_from_cam.coeffs());
    EXPECT_EQ(path.frames[i].fov_deg, path.frames[n - 1].fov_deg);
  }
  // ... and moving in between.
  const auto a = AsVec(P(path.frames[25])), b = AsVec(P(path.frames[24]));
  bool moved = false;
  for (int k = 0; k < 7; ++k) moved = moved || a[k] != b[k];
  EXPECT_TRUE(moved);
}

// Velocity is continuous: the change between frames never jumps by more
// than a small fraction of the largest change.
void ExpectSmooth(const CameraPath& path, int k) {
  double max_step = 0, max_jump = 0;
  for (size_t i = 2; i < path.frames.size(); ++i) {
    const double d1 = AsVec(P(path.frames[i]))[k] - AsVec(P(path.frames[i - 1]))[k];
    const double d0 = AsVec(P(path.frames[i - 1]))[k] - AsVec(P(path.frames[i - 2]))[k];
    max_step = std::max(max_step, std::abs(d1));
    max_jump = std::max(max_jump, std::abs(d1 - d0));
  }
  EXPECT_GT(max_step, 0);
  EXPECT_LT(max_jump, 0.08 * max_step);  // a velocity step would be ~1x
}

enum { X, Y, Z, PAN, TILT, ROLL, FOV };

TEST(SynthPresets, Table1MovesOnlyTheNamedParameters) {
  struct Case {
    const char* name;
    std::vector<int> params;
  };
  const std::vector<Case> cases = {{"crane_shot", {Y, TILT}}, {"dutch_angle", {ROLL}},
                                   {"arcing", {X, Z, PAN}},   {"traveling", {X}},
                                   {"tilting", {TILT}},       {"zoom_in", {FOV}},
                                   {"vertigo", {Z, FOV}}};
  ASSERT_EQ(SynthTable1PresetNames().size(), cases.size());
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const CameraPath path = SynthGroundTruth(c.name, Opts());
    ExpectStillEnds(path);
    const std::vector<bool> changed = Changed(path);
    for (int k = 0; k < 7; ++k) {
      const bool named = std::find(c.params.begin(), c.params.end(), k) != c.params.end();
      EXPECT_EQ(changed[k], named) << "parameter " << k;
    }
    for (int k : c.params) ExpectSmooth(path, k);
    for (const auto& f : path.frames) EXPECT_EQ(f.shot.value_or(-1), 0);
  }
}

TEST(SynthPresets, MagnitudesAndFraming) {
  const auto frames = [](const char* n) { return SynthGroundTruth(n, Opts()).frames; };
  auto t = frames("traveling");
  EXPECT_NEAR(t.front().center.x(), -2, 1e-12);
  EXPECT_NEAR(t.back().center.x(), 2, 1e-12);
  auto z = frames("zoom_in");
  EXPECT_NEAR(z.front().fov_deg, 60, 1e-12);
  EXPECT_NEAR(z.back().fov_deg, 30, 1e-12);
  EXPECT_FLOAT_EQ(*z.back().focal_px, 1280 / (2 * std::tan(DegToRad(15))));  // held as a float
  auto d = frames("dutch_angle");
  EXPECT_NEAR(P(d.back()).roll, 20, 1e-9);
  auto tl = frames("tilting");
  EXPECT_LT(P(tl.front()).tilt, 0);
  EXPECT_GT(P(tl.back()).tilt, 10);  // ends looking up: a low angle
  EXPECT_LT(tl.back().center.y(), synth::HallSubjectCenter().y());

  // Framing presets keep the characters in the middle of the picture.
  for (const char* n : {"crane_shot", "arcing"}) {
    SCOPED_TRACE(n);
    for (const auto& f : frames(n)) {
      synth::CameraView v;
      v.center = f.center;
      v.world_from_cam = f.world_from_cam;
      v.fov_deg = f.fov_deg;
      Eigen::Vector2d xy;
      ASSERT_TRUE(synth::ProjectToImage(v, synth::HallSubjectCenter(), &xy));
      EXPECT_NEAR(xy.x(), 640, 12);
      EXPECT_NEAR(xy.y(), 360, 1e-6);
    }
  }
  auto crane = frames("crane_shot");
  EXPECT_GT(crane.back().center.y() - crane.front().center.y(), 2.5);
  auto arc = frames("arcing");
  for (const auto& f : arc) {
    const Vector3d r = f.center - synth::HallSubjectCenter();
    EXPECT_NEAR(std::hypot(r.x(), r.z()), 4.6, 1e-9);
  }
  EXPECT_NEAR(P(arc.back()).pan - P(arc.front()).pan, 70, 1e-9);
}

TEST(SynthPresets, VertigoKeepsTheSubjectSize) {
  for (const char* n : {"vertigo", "dolly_zoom_parallax"}) {
    SCOPED_TRACE(n);
    const CameraPath path = SynthGroundTruth(n, Opts());
    const double z_subject = synth::HallSubjectCenter().z();
    const auto width_at_subject = [&](const CameraFrame& f) {
      return 2 * (f.center.z() - z_subject) * std::tan(DegToRad(f.fov_deg) / 2);
    };
    const double w0 = width_at_subject(path.frames.front());
    // 1e-6: the FOVs are floats (~1e-7 of their value).
    for (const auto& f : path.frames) EXPECT_NEAR(width_at_subject(f), w0, 1e-6);
    // Moves forward while the fov widens (a zoom out).
    EXPECT_LT(path.frames.back().center.z(), path.frames.front().center.z() - 3.9);
    EXPECT_GT(path.frames.back().fov_deg, path.frames.front().fov_deg + 30);
  }
}

TEST(SynthPresets, ModelColumnNamesTheTrueMotion) {
  const auto model_at = [](const char* n, int i) {
    return *SynthGroundTruth(n, Opts()).frames[i].model;
  };
  EXPECT_EQ(model_at("zoom_in", 0), "static");
  EXPECT_EQ(model_at("zoom_in", 80), "zoom");
  EXPECT_EQ(model_at("dutch_angle", 80), "rotation");
  EXPECT_EQ(model_at("tilting", 80), "rotation");
  EXPECT_EQ(model_at("traveling", 80), "general");
  // Dolly zooms translate *and* change the focal: the estimator's general+zoom.
  EXPECT_EQ(model_at("vertigo", 80), "general+zoom");
  EXPECT_EQ(model_at("dolly_zoom_parallax", 80), "general+zoom");
  EXPECT_EQ(model_at("crane_shot", 80), "general");
  EXPECT_EQ(model_at("telephoto_zoom_pan", 80), "rotation+zoom");
  EXPECT_EQ(model_at("traveling", 160), "static");
  for (const auto& f : SynthGroundTruth("static_camera", Opts()).frames) {
    EXPECT_EQ(*f.model, "static");
  }
}

TEST(SynthPresets, TimesAreFrameOverFps) {
  SynthOptions o = Opts();
  o.fps = 30;
  o.duration_s = 2;
  const CameraPath path = SynthGroundTruth("slow_pan", o);
  ASSERT_EQ(path.frames.size(), 60u);
  for (const auto& f : path.frames) EXPECT_DOUBLE_EQ(f.time_s, f.frame / 30.0);
  EXPECT_EQ(path.width(), 1280);
  EXPECT_EQ(path.height(), 720);
  EXPECT_DOUBLE_EQ(path.fps(), 30);
  EXPECT_EQ(path.metadata.at("preset"), "slow_pan");
}

TEST(SynthPresets, HardCutRestartsTheShot) {
  const CameraPath path = SynthGroundTruth("hard_cut", Opts());
  ASSERT_EQ(path.metadata.at("cut_frames"), "84");
  for (const auto& f : path.frames) EXPECT_EQ(*f.shot, f.frame < 84 ? 0 : 1);
  // A different camera setup after the cut.
  EXPECT_GT((path.frames[84].center - path.frames[83].center).norm(), 1.0);
  EXPECT_EQ(*path.frames[84].model, "general");
  EXPECT_EQ(*path.frames[60].model, "rotation");
}

TEST(SynthPresets, HandheldIsSeededAndSmall) {
  SynthOptions a = Opts(), b = Opts();
  b.seed = 2;
  const CameraPath pa = SynthGroundTruth("handheld_shake", a);
  const CameraPath pa2 = SynthGroundTruth("handheld_shake", a);
  const CameraPath pb = SynthGroundTruth("handheld_shake", b);
  double diff = 0;
  for (size_t i = 0; i < pa.frames.size(); ++i) {
    EXPECT_EQ(pa.frames[i].center, pa2.frames[i].center);
    diff = std::max(diff, (pa.frames[i].center - pb.frames[i].center).norm());
    EXPECT_LT(AngleBetweenDeg(pa.frames[i].world_from_cam, pa.frames[0].world_from_cam), 3.0);
    EXPECT_LT((pa.frames[i].center - pa.frames[0].center).norm(), 0.1);
  }
  EXPECT_GT(diff, 1e-3);
}

TEST(SynthPresets, WhipPanIsFastAndFadeReturns) {
  const CameraPath path = SynthGroundTruth("whip_pan", Opts());
  double max_deg_per_frame = 0;
  for (size_t i = 1; i < path.frames.size(); ++i) {
    max_deg_per_frame = std::max(max_deg_per_frame, AngleBetweenDeg(path.frames[i - 1].world_from_cam,
                                                                     path.frames[i].world_from_cam));
  }
  EXPECT_GT(max_deg_per_frame, 5);  // > 120 deg/s
  const auto& fade = synth::FindSynthPreset("fade_to_black");
  synth::ClipTiming timing;
  EXPECT_EQ(synth::PresetBrightnessAt(fade, 0.5, timing), 1);
  EXPECT_EQ(synth::PresetBrightnessAt(fade, 3.75, timing), 0);
  EXPECT_NEAR(synth::PresetBrightnessAt(fade, 3.0, timing), 0.5, 1e-12);
  EXPECT_EQ(synth::PresetBrightnessAt(fade, 6.5, timing), 1);
}

TEST(SynthPresets, MoversLeaveTheCameraPathAlone) {
  // The movers are no part of --all, and the ground truth is the camera's only.
  EXPECT_EQ(SynthMoverPresetNames().size(), 6u);
  const std::vector<std::string> all = SynthPresetNames();
  for (const std::string& name : SynthMoverPresetNames()) {
    EXPECT_EQ(std::count(all.begin(), all.end(), name), 0) << name;
  }
  const CameraPath head = SynthGroundTruth("head_turn", Opts());
  EXPECT_EQ(head.metadata.at("movers"), "head");
  for (const CameraFrame& f : head.frames) {
    EXPECT_EQ(f.model, "static");
    EXPECT_EQ(f.center, head.frames[0].center);
  }
  // The dark head_turn is head_turn's camera in another hall.
  const CameraPath dark = SynthGroundTruth("head_turn_dark", Opts());
  EXPECT_EQ(dark.metadata.at("scene"), "hall_dark_low_texture");
  ASSERT_EQ(dark.frames.size(), head.frames.size());
  EXPECT_EQ(dark.frames.back().center, head.frames.back().center);
  EXPECT_EQ(dark.frames.back().world_from_cam.coeffs(), head.frames.back().world_from_cam.coeffs());
  EXPECT_EQ(SynthGroundTruth("crowd_static", Opts()).frames.back().model, "static");
  // A camera move with walkers is the move without them.
  const CameraPath a = SynthGroundTruth("traveling_crossing", Opts());
  const CameraPath b = SynthGroundTruth("traveling", Opts());
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (size_t i = 0; i < a.frames.size(); ++i) {
    EXPECT_EQ(a.frames[i].center, b.frames[i].center);
    EXPECT_EQ(a.frames[i].world_from_cam.coeffs(), b.frames[i].world_from_cam.coeffs());
    EXPECT_EQ(a.frames[i].model, b.frames[i].model);
  }
  EXPECT_EQ(SynthGroundTruth("pan_crossing", Opts()).frames[80].model, "rotation");
  EXPECT_EQ(SynthGroundTruth("head_push_in", Opts()).frames[80].model, "general");
}

TEST(SynthPresets, VariantKeepsTheCameraPathAndRecordsItsLook) {
  SynthOptions test = Opts();
  test.variant = "test";
  for (const std::string& name : SynthPresetNames()) {
    const CameraPath a = SynthGroundTruth(name, Opts()), b = SynthGroundTruth(name, test);
    ASSERT_EQ(a.frames.size(), b.frames.size());
    for (size_t i = 0; i < a.frames.size(); ++i) {
      EXPECT_EQ(a.frames[i].center, b.frames[i].center);
      EXPECT_EQ(a.frames[i].world_from_cam.coeffs(), b.frames[i].world_from_cam.coeffs());
      EXPECT_EQ(a.frames[i].fov_deg, b.frames[i].fov_deg);
      EXPECT_EQ(a.frames[i].model, b.frames[i].model);
    }
    EXPECT_EQ(b.metadata.at("variant"), "test");
    EXPECT_EQ(b.metadata.at("distortion_k1"), "-0.04");
    EXPECT_EQ(b.metadata.at("movers"), "far_walkers");
    EXPECT_EQ(a.metadata.count("variant"), 0u);
    EXPECT_EQ(a.metadata.count("distortion_k1"), 0u);
  }
  // --distortion overrides the variant's k1 and works alone.
  SynthOptions k = Opts();
  k.has_distortion = true;
  k.distortion_k1 = 0.05;
  EXPECT_EQ(SynthGroundTruth("zoom_in", k).metadata.at("distortion_k1"), "0.05");
  k.distortion_k1 = 0.5;
  EXPECT_THROW(k.Check(), UsageError);
  test.variant = "other";
  EXPECT_THROW(test.Check(), UsageError);
}

TEST(SynthPresets, NamesAndErrors) {
  EXPECT_EQ(SynthPresetNames().size(), 17u);
  EXPECT_EQ(SynthHardPresetNames().size(), 10u);
  EXPECT_THROW(synth::FindSynthPreset("nope"), UsageError);
  SynthOptions o;
  o.width = 641;
  EXPECT_THROW(o.Check(), UsageError);
  o = SynthOptions();
  o.x264_preset = "turbo";
  EXPECT_THROW(o.Check(), UsageError);
}

}  // namespace
}  // namespace hapcine
