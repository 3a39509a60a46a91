#include "haptics/haptic_models.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "core/error.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using testing::MakeEffectPath;

using testing::MaxCoord;
using testing::MaxStep;

// A film: three shots, 60 s: a 25 s traveling drift (never stops), a 20 s
// shot with a zoom-in then a dutch angle, a 15 s crane; 25 fps, `shot` column.
CameraPath MakeFilm() {
  CameraPath path;
  path.metadata["fps"] = "25";
  const double fps = 25;
  int frame = 0;
  auto add = [&](double t, int shot, const Eigen::Vector3d& c, const PanTiltRoll& ptr, double fov) {
    CameraFrame f;
    f.frame = frame++;
    f.time_s = t;
    f.center = c;
    f.world_from_cam = QuaternionFromPanTiltRoll(ptr);
    f.fov_deg = fov;
    f.shot = shot;
    path.frames.push_back(f);
  };
  for (int i = 0; i < 25 * fps; ++i) {  // shot 0: 0.8 units/s sideways, forever
    add(i / fps, 0, Eigen::Vector3d(0.8 * i / fps, 0, 0), PanTiltRoll{}, 50);
  }
  for (int i = 0; i < 20 * fps; ++i) {  // shot 1 (a different world frame)
    const double t = i / fps;
    PanTiltRoll ptr{30, 0, t > 10 ? 3.0 * (t - 10) : 0};
    const double fov = t < 8 ? 50 - 3 * t : 26;
    add(25 + t, 1, Eigen::Vector3d(5, 1, -3), ptr, fov);
  }
  for (int i = 0; i < 15 * fps; ++i) {  // shot 2
    const double t = i / fps;
    add(45 + t, 2, Eigen::Vector3d(0, 0.3 * t, 0), PanTiltRoll{0, -t, 0}, 40);
  }
  return path;
}

TEST(HapticModels, NoneIsAllZeroAtTheRate) {
  HapticOptions o;
  o.model = HapticModel::kNone;
  o.source = "clip.camera.csv";
  const HapticTrack t = MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o);
  EXPECT_EQ(t.model, "none");
  EXPECT_EQ(t.source, "clip.camera.csv");
  EXPECT_DOUBLE_EQ(t.rate_hz, 100);  // the stored default: the player interpolates to 1 kHz
  EXPECT_EQ(t.interpolation, TrackInterpolation::kMonotoneCubic);
  EXPECT_EQ(t.samples.size(), 701u);  // 0 .. 7 s inclusive
  EXPECT_NEAR(t.samples.back().time_s, 7.0, 1e-9);
  EXPECT_EQ(MaxCoord(t), 0.0);
  EXPECT_FALSE(t.samples[0].shot.has_value());  // the path had no shot column
}

TEST(HapticModels, EveryModelMakesAValidTrack) {
  for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic, HapticModel::kRandom,
                        HapticModel::kNone}) {
    HapticOptions o;
    o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
    o.model = m;
    o.rate_hz = 200;
    const HapticTrack t = MakeHapticTrack(MakeEffectPath(CameraEffect::kDutchAngle), o);
    // The rows at 200 Hz, and a semantic track's 1 kHz rows where it has kinks.
    const auto dense = t.metadata.find("dense_rows");
    EXPECT_EQ(m == HapticModel::kSemantic, dense != t.metadata.end()) << HapticModelName(m);
    EXPECT_EQ(t.samples.size() - (dense == t.metadata.end() ? 0 : std::stoul(dense->second)), 1401u);
    EXPECT_LE(MaxCoord(t), o.seat.usable_half_m + 1e-12) << HapticModelName(m);
    EXPECT_EQ(t.metadata.at("clamped_samples"), "0");
    std::stringstream ss;
    WriteHapticTrack(t, ss);
    const HapticTrack back = ReadHapticTrack(ss, "x");
    EXPECT_EQ(back.samples.size(), t.samples.size());
    EXPECT_EQ(back.model, HapticModelName(m));
    if (m != HapticModel::kNone && m != HapticModel::kRandom) {
      EXPECT_GT(MaxCoord(t), 0.02) << HapticModelName(m);
    }
  }
}

TEST(HapticModels, SemanticFromClassifierLabelsTheEffectColumn) {
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.model = HapticModel::kSemantic;
  const HapticTrack t = MakeHapticTrack(MakeEffectPath(CameraEffect::kZoomIn), o);
  ASSERT_TRUE(t.samples[3500].effect.has_value());
  EXPECT_EQ(*t.samples[3500].effect, "zoom_in");
  EXPECT_EQ(*t.samples[100].effect, "none");
  EXPECT_LT(t.samples[3250].pos_m[2].z(), -0.01);  // walking forward
}

// Largest distance between what a player renders from `stored` and from
// `reference` (a 1 kHz track): at every reference row and half-way between.
double RenderedDistanceM(const HapticTrack& reference, const HapticTrack& stored) {
  double worst = 0;
  Eigen::Vector3d a[kNumActuators], b[kNumActuators];
  const auto& r = reference.samples;
  for (size_t i = 0; i + 1 < r.size(); ++i) {
    for (const double t : {r[i].time_s, 0.5 * (r[i].time_s + r[i + 1].time_s)}) {
      reference.Sample(t, a);
      stored.Sample(t, b);
      for (int k = 0; k < kNumActuators; ++k) worst = std::max(worst, (a[k] - b[k]).norm());
    }
  }
  return worst;
}

TEST(HapticModels, SemanticAtTheStoredRateRendersWithinATenthOfAMillimetreOfOneKilohertz) {
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/haptic_models_test_rate.csv";
  {
    // A dutch angle stops at the centre while it moves (a kink); the tilt's
    // release is cut to 40 ms by the next effect, faster than the speed
    // limit, whose ramp then starts at the first row past the limit.
    std::ofstream out(file);
    out << "start_s,end_s,effect,intensity\n0.5,2.3,dutch_angle,1\n2.5,4.46,tilting,1\n"
           "4.5,6.5,traveling,1\n";
  }
  HapticOptions o;
  o.model = HapticModel::kSemantic;
  o.keyframes_file = file;
  const CameraPath path = MakeEffectPath(CameraEffect::kTraveling);
  o.rate_hz = 1000;
  const HapticTrack reference = MakeHapticTrack(path, o);
  EXPECT_EQ(reference.metadata.count("dense_rows"), 0u);  // 1 kHz: every row already
  EXPECT_GT(std::stoi(reference.metadata.at("rate_limited_samples")), 0);
  o.rate_hz = 0;  // the stored default, 100 Hz
  const HapticTrack stored = MakeHapticTrack(path, o);
  std::remove(file.c_str());
  EXPECT_LT(RenderedDistanceM(reference, stored), 0.1e-3);
  // 1 kHz rows around the kinks and the limited ramp only: far from the
  // 7001 rows of a 1 kHz track.
  const size_t dense = std::stoul(stored.metadata.at("dense_rows"));
  EXPECT_GT(dense, 0u);
  EXPECT_LT(stored.samples.size(), 2 * 701u);
  EXPECT_EQ(stored.samples.size(), 701u + dense);
  // The rows read back as written, times included.
  std::stringstream ss;
  WriteHapticTrack(stored, ss);
  EXPECT_LT(RenderedDistanceM(reference, ReadHapticTrack(ss, "x")), 0.1e-3);
}

TEST(HapticModels, SemanticFromKeyframesFile) {
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/haptic_models_test_fx.csv";
  {
    std::ofstream out(file);
    out << "start_s,end_s,effect,intensity\n2,4,inferiority,0.5\n";
  }
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.model = HapticModel::kSemantic;
  o.keyframes_file = file;
  const HapticTrack t = MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o);
  EXPECT_NEAR(t.samples[4000].pos_m[0].y(), -0.5 * o.seat.usable_half_m, 1e-9);
  EXPECT_EQ(*t.samples[3000].effect, "tilting");
  std::remove(file.c_str());
  EXPECT_THROW(MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o), Error);
  o.model = HapticModel::kCinematic;
  EXPECT_THROW(o.Check(), UsageError);  // keyframes are for the semantic model
}

TEST(HapticModels, FilmStaysInTheWorkspaceAndNeverJumps) {
  const CameraPath film = MakeFilm();
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.source = "film.camera.csv";
  const HapticTrack t = MakeHapticTrack(film, o);
  EXPECT_NEAR(t.duration_s(), 59.96, 1e-6);
  const double max_step_bound = o.washout.max_speed_m_s / o.OutputRateHz();  // 0.5 mm
  EXPECT_LE(MaxCoord(t), o.seat.usable_half_m + 1e-12);
  EXPECT_LE(MaxStep(t), max_step_bound + 1e-15);
  EXPECT_EQ(t.metadata.at("clamped_samples"), "0");
  // The shot column is carried through.
  EXPECT_EQ(*t.samples[10000].shot, 0);
  EXPECT_EQ(*t.samples[30000].shot, 1);
  EXPECT_EQ(*t.samples[50000].shot, 2);
  // Around each cut the motion is smooth: the largest step within 0.5 s after
  // the cut is below the crossfade's own bound (1.875 * 0.09 m / 0.5 s).
  for (double cut : {25.0, 45.0}) {
    const size_t c = static_cast<size_t>(cut * 1000);
    double m = 0;
    for (size_t i = c - 5; i < c + 500; ++i) {
      for (int a = 0; a < kNumActuators; ++a) {
        m = std::max(m, (t.samples[i + 1].pos_m[a] - t.samples[i].pos_m[a]).cwiseAbs().maxCoeff());
      }
    }
    EXPECT_LE(m, 1.875 * 0.09 / 0.5 / 1000 + 1e-9) << cut;
  }
  // Measured, for docs/haptics.md.
  double max_acc = 0;
  for (size_t i = 2; i < t.samples.size(); ++i) {
    for (int a = 0; a < kNumActuators; ++a) {
      const Eigen::Vector3d acc =
          (t.samples[i].pos_m[a] - 2 * t.samples[i - 1].pos_m[a] + t.samples[i - 2].pos_m[a]) * 1e6;
      max_acc = std::max(max_acc, acc.cwiseAbs().maxCoeff());
    }
  }
  std::cout << "[ film ] max |coord| " << MaxCoord(t) << " m, max step " << MaxStep(t)
            << " m, max accel " << max_acc << " m/s^2, rate-limited samples "
            << t.metadata.at("rate_limited_samples") << "\n";
  // Without the washout the drift holds at the edge of the usable range but
  // still never leaves it.
  o.washout.mode = WashoutMode::kOff;
  const HapticTrack raw = MakeHapticTrack(film, o);
  EXPECT_LE(MaxCoord(raw), o.seat.usable_half_m + 1e-12);
  EXPECT_LE(MaxStep(raw), max_step_bound + 1e-15);
  EXPECT_EQ(raw.metadata.at("clamped_samples"), "0");
  EXPECT_NEAR(raw.samples[24900].pos_m[0].x(), o.seat.usable_half_m, 1e-3);
  // The default (adaptive) washout never moves back while the drift goes on:
  // it holds, and the cut returns it. (It was the second-order high-pass,
  // which returned to the centre during the drift: a false cue.)
  for (int i = 1000; i < 24900; i += 100) {
    EXPECT_GE(t.samples[i].pos_m[0].x(), t.samples[i - 100].pos_m[0].x() - 1e-3) << i;
  }
  // It is felt sooner than with scaling alone (a 7 s window's gain)...
  EXPECT_GT(t.samples[5000].pos_m[0].x(), 2 * raw.samples[5000].pos_m[0].x());
  // ... and holds near the edge.
  EXPECT_GT(t.samples[24900].pos_m[0].x(), 0.8 * o.seat.usable_half_m);
  // The high-pass washout returns close to the centre during the drift.
  o.washout.mode = WashoutMode::kHighPass;
  const HapticTrack hp = MakeHapticTrack(film, o);
  EXPECT_LT(std::abs(hp.samples[24900].pos_m[0].x()), 0.1 * o.seat.usable_half_m);
}

// 10 s of a pan (3 deg/s) with a sideways drift; frames 100-149 (4-6 s)
// lost: the placeholder is frame 99's pose, and at frame 150 the path jumps
// by the 2 s of motion nothing measured.
CameraPath PanWithLostFrames() {
  CameraPath path;
  for (int i = 0; i < 250; ++i) {
    const int placed = i >= 100 && i < 150 ? 99 : i;
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 25.0;
    f.center = Eigen::Vector3d(0.02 * placed / 25.0, 0, 0);
    f.world_from_cam = QuaternionFromPanTiltRoll(PanTiltRoll{3.0 * placed / 25.0, 0, 0});
    f.fov_deg = 50;
    f.shot = 0;
    f.model = placed == i ? "general" : kLostModel;
    f.confidence = placed == i ? 0.9 : 0.0;
    path.frames.push_back(f);
  }
  return path;
}

TEST(HapticModels, LostFramesFadeToRestAndResumeWithoutASpike) {
  const CameraPath path = PanWithLostFrames();
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.washout.mode = WashoutMode::kOff;  // a held pose would hold the actuators without it
  const HapticTrack t = MakeHapticTrack(path, o);
  const double rate = o.OutputRateHz();
  // At rest once the ramp from the last placed frame (3.96 s) is over, until the motion resumes at 6 s.
  // (+ one frame: samples interpolate between frames)
  for (double s = 3.96 + o.washout.cut_ramp_s + 0.04; s < 6.0; s += 0.01) {
    const HapticSample& x = t.samples[static_cast<size_t>(s * rate)];
    for (int a = 0; a < kNumActuators; ++a) EXPECT_LT(x.pos_m[a].norm(), 1e-12) << s;
  }
  // Before the gap the pan is felt; after it, the motion resumes from rest.
  EXPECT_GT(t.samples[static_cast<size_t>(3.9 * rate)].pos_m[0].norm(), 1e-3);
  EXPECT_GT(t.samples[static_cast<size_t>(9.9 * rate)].pos_m[0].norm(), 1e-3);
  // No spike: the speed limit never acts, and no step is larger than the
  // placed motion's own largest step before the gap (times the crossfade's 1.875).
  EXPECT_EQ(t.metadata.at("rate_limited_samples"), "0");
  double before = 0, overall = 0;
  for (size_t i = 1; i < t.samples.size(); ++i) {
    for (int a = 0; a < kNumActuators; ++a) {
      const double step = (t.samples[i].pos_m[a] - t.samples[i - 1].pos_m[a]).cwiseAbs().maxCoeff();
      overall = std::max(overall, step);
      if (t.samples[i].time_s < 3.9) before = std::max(before, step);
    }
  }
  // The fade's own largest step: 1.875 x the value it removes / the ramp.
  double at_gap = 0;
  for (int a = 0; a < kNumActuators; ++a)
    at_gap = std::max(at_gap, t.samples[static_cast<size_t>(3.96 * rate)].pos_m[a].cwiseAbs().maxCoeff());
  EXPECT_LE(overall, before + 1.875 * at_gap / (o.washout.cut_ramp_s * rate) + 1e-12);
  std::cout << "[ lost ] largest step " << overall << " m, before the gap " << before << " m\n";
  // The semantic model sees no motion over the lost frames (no jump to classify).
  o.model = HapticModel::kSemantic;
  const HapticTrack sem = MakeHapticTrack(path, o);
  EXPECT_EQ(sem.metadata.at("rate_limited_samples"), "0");
}

TEST(HapticModels, RejectsBadPaths) {
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.source = "bad.camera.csv";
  CameraPath gap = MakeEffectPath(CameraEffect::kTraveling);
  for (size_t i = 100; i < gap.frames.size(); ++i) gap.frames[i].time_s += 2.0;
  try {
    MakeHapticTrack(gap, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.camera.csv: frame 100"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("time gap"), std::string::npos);
  }
  // The same gap at a shot boundary is fine.
  for (size_t i = 0; i < gap.frames.size(); ++i) gap.frames[i].shot = i < 100 ? 0 : 1;
  EXPECT_NO_THROW(MakeHapticTrack(gap, o));
  // Not a jump of 1000 s there: the track would span it (1e6 samples for a
  // path of a few seconds).
  for (size_t i = 100; i < gap.frames.size(); ++i) gap.frames[i].time_s += 1000.0;
  try {
    MakeHapticTrack(gap, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.camera.csv: frame 100"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("at the change to shot 1"), std::string::npos);
  }
  CameraPath absurd = MakeEffectPath(CameraEffect::kTraveling);
  absurd.frames[5].center.x() = 2e6;
  EXPECT_THROW(MakeHapticTrack(absurd, o), Error);
  CameraPath nan = MakeEffectPath(CameraEffect::kTraveling);
  nan.frames[5].center.y() = std::nan("");
  EXPECT_THROW(MakeHapticTrack(nan, o), Error);
  CameraPath back = MakeEffectPath(CameraEffect::kTraveling);
  back.frames[5].time_s = back.frames[4].time_s;
  EXPECT_THROW(MakeHapticTrack(back, o), Error);
  EXPECT_THROW(MakeHapticTrack(CameraPath(), o), Error);
  // A single frame is a valid (still) path.
  CameraPath one = MakeEffectPath(CameraEffect::kTraveling);
  one.frames.resize(1);
  EXPECT_EQ(MakeHapticTrack(one, o).samples.size(), 1u);
  EXPECT_THROW(HapticModelFromName("cinema"), UsageError);
}

// Whatever a camera path holds that ReadCameraPath and the haptic checks
// accept (huge but legal positions, wild rotations, FOV anywhere in (0, 180),
// irregular times, many short shots), no model leaves the 0.10 m cube, and
// the cinematic scaling alone keeps it inside the usable range: the final
// clamp never has to act.
TEST(HapticModels, NoAcceptedPathLeavesTheWorkspace) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    CameraPath p;
    const int n = 2 + static_cast<int>(u(rng) * 300);
    const double pos_scale = std::pow(10.0, -6 + 11.5 * u(rng));  // 1e-6 .. 3e5
    double t = 10 * u(rng);
    int shot = 0;
    for (int i = 0; i < n; ++i) {
      CameraFrame f;
      f.frame = i;
      t += 0.001 + 0.3 * u(rng);
      f.time_s = t;
      for (int k = 0; k < 3; ++k) f.center[k] = pos_scale * (2 * u(rng) - 1);
      f.world_from_cam = Eigen::Quaterniond(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5,
                                            u(rng) - 0.5).normalized();
      f.fov_deg = 0.01 + 179.98 * u(rng);
      if (trial % 2 == 0 && u(rng) < 0.05) ++shot;
      if (trial % 2 == 0) f.shot = shot;
      p.frames.push_back(f);
    }
    for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic, HapticModel::kRandom}) {
      HapticOptions o;
      o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
      o.model = m;
      o.rate_hz = 200;
      o.cinematic.per_film_scaling = trial % 4 == 0;
      for (WashoutMode washout :
           {WashoutMode::kAdaptive, WashoutMode::kHighPass, WashoutMode::kOff}) {
        o.washout.mode = washout;
        const HapticTrack track = MakeHapticTrack(p, o);
        EXPECT_LE(MaxCoord(track), o.seat.usable_half_m + 1e-12) << trial << " " << track.model;
        EXPECT_EQ(track.metadata.at("clamped_samples"), "0") << trial << " " << track.model;
        for (const auto& s : track.samples)
          for (const auto& a : s.pos_m) ASSERT_TRUE(a.allFinite());
      }
    }
  }
}

// A media clock near 1e15 s is valid input, but there neighbouring doubles
// are 0.125 s apart: the track counts from the first frame, keeps the origin
// in its metadata, and is the track of the same path starting at 0.
TEST(HapticModels, HugeMediaClockCountsFromTheFirstFrame) {
  CameraPath at_zero = MakeEffectPath(CameraEffect::kTraveling);
  CameraPath far = at_zero;
  for (size_t i = 0; i < at_zero.frames.size(); ++i) {
    at_zero.frames[i].time_s = 0.125 * static_cast<double>(i);
    far.frames[i].time_s = 1e15 + 0.125 * static_cast<double>(i);
  }
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.source = "far.camera.csv";
  const HapticTrack a = MakeHapticTrack(at_zero, o);
  const HapticTrack b = MakeHapticTrack(far, o);
  EXPECT_EQ(b.metadata.at("time_origin_s"), "1e+15");
  EXPECT_EQ(a.metadata.count("time_origin_s"), 0u);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) {
    ASSERT_EQ(a.samples[i].time_s, b.samples[i].time_s) << i;
    for (int k = 0; k < kNumActuators; ++k) ASSERT_EQ(a.samples[i].pos_m[k], b.samples[i].pos_m[k]);
  }
  std::stringstream written;
  WriteHapticTrack(b, written);  // threw "time not increasing at sample 1"
  EXPECT_EQ(ReadHapticTrack(written, "far.haptic.csv").samples.size(), b.samples.size());
}

TEST(HapticModels, DifferenceOfTracks) {
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  const CameraPath path = MakeEffectPath(CameraEffect::kTraveling);
  const HapticTrack a = MakeHapticTrack(path, o);
  HapticDifference d = HapticTrackDifference(a, a);
  EXPECT_EQ(d.num_samples, a.samples.size());
  for (int k = 0; k < kNumActuators; ++k) EXPECT_EQ(d.max_m[k], 0.0);
  HapticTrack b = a;
  for (auto& s : b.samples) s.pos_m[1] += Eigen::Vector3d(0.003, 0, 0.004);  // 5 mm
  d = HapticTrackDifference(a, b);
  EXPECT_NEAR(d.rms_m[1], 0.005, 1e-12);
  EXPECT_NEAR(d.max_m[1], 0.005, 1e-12);
  EXPECT_EQ(d.rms_m[0], 0.0);
  EXPECT_EQ(HapticTrackDifference(a, HapticTrack()).num_samples, 0u);
}

// Each film gets its own noise by default (a content hash), the same film
// always the same; --seed fixes it.
TEST(HapticModels, RandomSeedComesFromTheFilmUnlessGiven) {
  const CameraPath a = MakeEffectPath(CameraEffect::kTraveling);
  const CameraPath b = MakeEffectPath(CameraEffect::kZoomIn);
  HapticOptions o;
  o.model = HapticModel::kRandom;
  o.rate_hz = 100;
  const HapticTrack ta = MakeHapticTrack(a, o), ta2 = MakeHapticTrack(a, o);
  const HapticTrack tb = MakeHapticTrack(b, o);
  EXPECT_EQ(ta.metadata.at("seed"), std::to_string(DefaultRandomSeed(a)));
  EXPECT_EQ(ta.metadata.at("seed_from"), "content");
  EXPECT_NE(DefaultRandomSeed(a), DefaultRandomSeed(b));
  EXPECT_EQ(ta.samples[300].pos_m[1], ta2.samples[300].pos_m[1]);
  EXPECT_NE(ta.samples[300].pos_m[1], tb.samples[300].pos_m[1]);
  CameraPath moved = a;  // one coordinate of one frame changes the noise
  moved.frames[50].center.x() += 1e-9;
  EXPECT_NE(DefaultRandomSeed(moved), DefaultRandomSeed(a));
  o.seed = 7;
  const HapticTrack fa = MakeHapticTrack(a, o), fb = MakeHapticTrack(b, o);
  EXPECT_EQ(fa.metadata.at("seed"), "7");
  EXPECT_EQ(fa.metadata.at("seed_from"), "option");
  EXPECT_EQ(fa.samples[300].pos_m[1], fb.samples[300].pos_m[1]);
  // Comparable tracks share one noise (the reference's).
  o.seed.reset();
  const auto [ca, cb] = MakeComparableHapticTracks(a, b, o);
  EXPECT_EQ(ca.samples[300].pos_m[1], cb.samples[300].pos_m[1]);
}

TEST(HapticModels, ComparableTracksShareTheScaling) {
  // An "estimate" that travels 20 % too far: with its own scaling it would
  // also fill the workspace and look perfect; with the reference's scaling
  // the difference shows.
  const CameraPath ref = MakeEffectPath(CameraEffect::kTraveling, 1.0);
  const CameraPath est = MakeEffectPath(CameraEffect::kTraveling, 1.2);
  HapticOptions o;
  o.rate_hz = 1000;  // the sample indices and bounds below are at 1 kHz
  o.washout.mode = WashoutMode::kOff;
  const HapticDifference own =
      HapticTrackDifference(MakeHapticTrack(ref, o), MakeHapticTrack(est, o));
  EXPECT_LT(own.max_m[0], 1e-9);
  const auto [a, b] = MakeComparableHapticTracks(ref, est, o);
  const HapticDifference same = HapticTrackDifference(a, b);
  // The estimate runs 20 % ahead (0.054 p vs 0.045 p at progress p) until the
  // clamp stops it at 0.048: the largest gap is 0.2 * 0.048 / 1.2 = 8 mm.
  EXPECT_NEAR(same.max_m[0], 0.2 * 0.048 / 1.2, 1e-4);
  EXPECT_GT(std::stoi(b.metadata.at("clamped_samples")), 0);
}

}  // namespace
}  // namespace hapcine

// ---- Edits (haptic_edits.h) ----

namespace hapcine {
namespace {

using testing::MaxCoord;
using testing::MaxStep;
using testing::MakeEffectPath;


// MakeFilm's shots: 0 = [0, 25) s, 1 = [25, 45) s, 2 = [45, 60) s.
constexpr double kCut1 = 25, kCut2 = 45;

HapticOptions FilmOptions(HapticModel model = HapticModel::kCinematic) {
  HapticOptions o;
  o.model = model;
  o.source = "film.camera.csv";
  return o;  // 100 Hz
}

ShotEdit Shot(int shot) {
  ShotEdit e;
  e.shot = shot;
  return e;
}

std::string TrackText(const HapticTrack& t) {
  std::stringstream ss;
  WriteHapticTrack(t, ss);
  return ss.str();
}

// Largest |a - b| of any coordinate over the rows both tracks have (same
// time: a semantic track adds dense rows between the regular ones) with
// from <= t < to.
double MaxDifference(const HapticTrack& a, const HapticTrack& b, double from, double to) {
  double m = 0;
  size_t common = 0;
  for (size_t i = 0, j = 0; i < a.samples.size() && j < b.samples.size();) {
    const double ta = a.samples[i].time_s, tb = b.samples[j].time_s;
    if (ta < tb - 1e-9) { ++i; continue; }
    if (tb < ta - 1e-9) { ++j; continue; }
    if (ta >= from - 1e-9 && ta < to - 1e-9) {
      ++common;
      for (int k = 0; k < kNumActuators; ++k) {
        m = std::max(m, (a.samples[i].pos_m[k] - b.samples[j].pos_m[k]).cwiseAbs().maxCoeff());
      }
    }
    ++i;
    ++j;
  }
  EXPECT_GT(common, 0u);
  return m;
}

double MaxAbs(const HapticTrack& a, double from, double to) {
  HapticTrack zero = a;
  for (HapticSample& s : zero.samples) {
    for (Eigen::Vector3d& p : s.pos_m) p.setZero();
  }
  return MaxDifference(a, zero, from, to);
}


TEST(HapticModelEdits, NoEditsIsTheSameFileAndNeutralEditsTheSameSamples) {
  const CameraPath film = MakeFilm();
  const HapticTrack plain = MakeHapticTrack(film, FilmOptions());
  HapticOptions o = FilmOptions();
  o.edits = HapticEdits{};
  o.edits.revision = 12;  // the studio's counter changes nothing
  EXPECT_EQ(TrackText(MakeHapticTrack(film, o)), TrackText(plain));
  // Entries that change nothing (gain 1, the film's own model and washout)
  // leave every sample as it was; only the metadata names the shots.
  ShotEdit same = Shot(1);
  same.gain = 1;
  same.mute = false;
  same.model = HapticModel::kCinematic;
  same.washout = WashoutEdit{};
  same.washout->mode = "adaptive";
  o.edits.shots = {Shot(0), same};
  const HapticTrack neutral = MakeHapticTrack(film, o);
  EXPECT_EQ(MaxDifference(neutral, plain, 0, 1e9), 0.0);
  EXPECT_EQ(neutral.metadata.at("edited_shots"), "0;1");
  EXPECT_EQ(plain.metadata.count("edited_shots"), 0u);
}

TEST(HapticModelEdits, GainZeroSilencesOneShotAndLeavesTheOthers) {
  const CameraPath film = MakeFilm();
  const HapticOptions plain_options = FilmOptions();
  const HapticTrack plain = MakeHapticTrack(film, plain_options);
  HapticOptions o = FilmOptions();
  ShotEdit e = Shot(1);
  e.gain = 0;
  o.edits.shots = {e};
  const HapticTrack silent = MakeHapticTrack(film, o);
  const double ramp = o.washout.cut_ramp_s;
  ASSERT_GT(MaxAbs(plain, kCut1 + ramp, kCut2), 0.01);  // the shot did move
  // Zero after the crossfade into it; the other shots untouched, except the
  // crossfade out of it, which starts from zero instead of its last value.
  EXPECT_EQ(MaxAbs(silent, kCut1 + ramp, kCut2), 0.0);
  EXPECT_EQ(MaxDifference(silent, plain, 0, kCut1), 0.0);
  EXPECT_EQ(MaxDifference(silent, plain, kCut2 + ramp, 1e9), 0.0);
  EXPECT_GT(MaxDifference(silent, plain, kCut2, kCut2 + ramp), 0.0);
  EXPECT_LE(MaxStep(silent), o.washout.max_speed_m_s / o.OutputRateHz() + 1e-15);
  // Mute is gain 0.
  ShotEdit muted = Shot(1);
  muted.mute = true;
  muted.gain = 3;
  o.edits.shots = {muted};
  EXPECT_EQ(TrackText(MakeHapticTrack(film, o)), TrackText(silent));
  // Half the gain, half the displacement (away from the crossfades).
  ShotEdit half = Shot(1);
  half.gain = 0.5;
  o.edits.shots = {half};
  const HapticTrack halved = MakeHapticTrack(film, o);
  for (size_t i = 0; i < halved.samples.size(); i += 7) {
    const double t = halved.samples[i].time_s;
    if (t < kCut1 + ramp || t >= kCut2) continue;
    for (int k = 0; k < kNumActuators; ++k) {
      EXPECT_LT((halved.samples[i].pos_m[k] - 0.5 * plain.samples[i].pos_m[k]).norm(), 1e-15) << t;
    }
  }
}

TEST(HapticModelEdits, ModelOverrideInOneShotIsThatModelThere) {
  const CameraPath film = MakeFilm();
  const HapticTrack cinematic = MakeHapticTrack(film, FilmOptions());
  const HapticTrack semantic = MakeHapticTrack(film, FilmOptions(HapticModel::kSemantic));
  HapticOptions o = FilmOptions();
  ShotEdit s1 = Shot(1), s2 = Shot(2);
  s1.model = HapticModel::kSemantic;
  s2.model = HapticModel::kNone;
  o.edits.shots = {s1, s2};
  const HapticTrack mixed = MakeHapticTrack(film, o);
  const double ramp = o.washout.cut_ramp_s;
  ASSERT_GT(MaxDifference(cinematic, semantic, kCut1 + ramp, kCut2), 0.01);
  EXPECT_EQ(MaxDifference(mixed, cinematic, 0, kCut1), 0.0);
  EXPECT_LT(MaxDifference(mixed, semantic, kCut1 + ramp, kCut2), 1e-12);
  EXPECT_EQ(MaxAbs(mixed, kCut2 + ramp, 1e9), 0.0);
  EXPECT_EQ(mixed.model, "cinematic");  // the film's model; the shots are listed
  EXPECT_EQ(mixed.metadata.at("edited_shots"), "1;2");
  EXPECT_EQ(mixed.metadata.at("effects_from"), "classifier");
  // The semantic shot is labelled with its effects, the others with none.
  bool labelled = false;
  for (const HapticSample& s : mixed.samples) {
    ASSERT_TRUE(s.effect.has_value());
    if (s.time_s < kCut1 || s.time_s >= kCut2) {
      EXPECT_EQ(*s.effect, "none");
    }
    labelled = labelled || *s.effect != "none";
  }
  EXPECT_TRUE(labelled);
  // The reverse: a cinematic shot in a semantic film is the cinematic model's shot.
  HapticOptions r = FilmOptions(HapticModel::kSemantic);
  ShotEdit c1 = Shot(1);
  c1.model = HapticModel::kCinematic;
  r.edits.shots = {c1};
  EXPECT_LT(MaxDifference(MakeHapticTrack(film, r), cinematic, kCut1 + ramp, kCut2), 1e-12);
  // A random shot moves, stays in the usable range, and is the same twice.
  ShotEdit n0 = Shot(0);
  n0.model = HapticModel::kRandom;
  o.edits.shots = {n0};
  const HapticTrack noisy = MakeHapticTrack(film, o);
  EXPECT_GT(MaxAbs(noisy, 0, kCut1), 0.005);
  EXPECT_LE(MaxCoord(noisy), o.seat.usable_half_m + 1e-12);
  EXPECT_EQ(TrackText(MakeHapticTrack(film, o)), TrackText(noisy));
  EXPECT_EQ(MaxDifference(noisy, cinematic, kCut1 + ramp, 1e9), 0.0);
}

TEST(HapticModelEdits, WashoutOverrideActsInItsShotOnly) {
  const CameraPath film = MakeFilm();
  const HapticTrack adaptive = MakeHapticTrack(film, FilmOptions());
  HapticOptions hp_options = FilmOptions();
  hp_options.washout.mode = WashoutMode::kHighPass;
  hp_options.washout.tau_s = 2;
  const HapticTrack highpass = MakeHapticTrack(film, hp_options);
  HapticOptions o = FilmOptions();
  ShotEdit e = Shot(0);  // the 25 s drift
  e.washout = WashoutEdit{};
  e.washout->mode = "highpass";
  e.washout->tau_s = 2;
  o.edits.shots = {e};
  const HapticTrack mixed = MakeHapticTrack(film, o);
  ASSERT_GT(MaxDifference(adaptive, highpass, 0, kCut1), 0.01);
  EXPECT_LT(MaxDifference(mixed, highpass, 0, kCut1), 1e-12);
  EXPECT_EQ(MaxDifference(mixed, adaptive, kCut1 + o.washout.cut_ramp_s, 1e9), 0.0);
  // One scaling for the whole film: the shot still equals the film-level track there.
  hp_options.cinematic.per_film_scaling = o.cinematic.per_film_scaling = true;
  EXPECT_LT(MaxDifference(MakeHapticTrack(film, o), MakeHapticTrack(film, hp_options), 0, kCut1),
            1e-12);
  o.cinematic.per_film_scaling = false;
  // A washout setting the command line would refuse is refused here too.
  e.washout->tau_s = 0.01;
  o.edits.shots = {e};
  try {
    MakeHapticTrack(film, o);
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("edits: shot 0: washout tau_s"), std::string::npos)
        << err.what();
  }
}

TEST(HapticModelEdits, KeyframesReplaceTheClassifier) {
  const CameraPath path = MakeEffectPath(CameraEffect::kTraveling);
  HapticOptions o;
  o.rate_hz = 1000;
  o.model = HapticModel::kSemantic;
  const std::vector<EffectSegment> classified = EffectiveEffectSegments(path, o);
  ASSERT_FALSE(classified.empty());
  EXPECT_EQ(classified[0].effect, CameraEffect::kTraveling);
  EffectSegment tilt;
  tilt.start_s = 2;
  tilt.end_s = 4;
  tilt.effect = CameraEffect::kTilting;
  tilt.intensity = 0.5;
  o.edits.keyframes = std::vector<EffectSegment>{tilt};
  const std::vector<EffectSegment> effective = EffectiveEffectSegments(path, o);
  ASSERT_EQ(effective.size(), 1u);
  EXPECT_EQ(effective[0].effect, CameraEffect::kTilting);
  const HapticTrack t = MakeHapticTrack(path, o);
  EXPECT_NEAR(t.samples[4000].pos_m[0].y(), -0.5 * o.seat.usable_half_m, 1e-9);
  EXPECT_EQ(*t.samples[3000].effect, "tilting");
  EXPECT_EQ(*t.samples[1500].effect, "none");  // the classifier's traveling is gone
  EXPECT_EQ(t.metadata.at("effects_from"), "edits");
  EXPECT_EQ(t.metadata.at("effect_segments"), "1");
  // An empty list replaces the classifier by nothing: a still track.
  o.edits.keyframes = std::vector<EffectSegment>{};
  EXPECT_EQ(MaxCoord(MakeHapticTrack(path, o)), 0.0);
}

TEST(HapticModelEdits, GainFourOnAnExtremePathStaysInTheWorkspace) {
  const CameraPath film = MakeFilm();  // its drift holds at the edge of the usable range
  for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic, HapticModel::kRandom}) {
    HapticOptions o = FilmOptions(m);
    for (int shot : {0, 1, 2}) {
      ShotEdit e = Shot(shot);
      e.gain = kMaxShotGain;
      o.edits.shots.push_back(e);
    }
    const HapticTrack t = MakeHapticTrack(film, o);
    EXPECT_LE(MaxCoord(t), o.seat.clamp_half_m + 1e-15) << HapticModelName(m);
    EXPECT_LE(MaxStep(t), o.washout.max_speed_m_s / o.OutputRateHz() + 1e-15);
    if (m == HapticModel::kCinematic) {
      EXPECT_GT(MaxCoord(t), o.seat.usable_half_m);  // it did push: the clamp held it
      EXPECT_NE(t.metadata.at("clamped_samples"), "0");
    }
  }
}

TEST(HapticModelEdits, AShotNotInThePathIsAnErrorNamingIt) {
  HapticOptions o = FilmOptions();
  o.edits.shots = {Shot(1), Shot(7)};
  try {
    MakeHapticTrack(MakeFilm(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "film.camera.csv");
    EXPECT_NE(e.reason().find("shot 7 is not in the camera path"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CheckEditsForPath(MakeFilm(), o), Error);  // before making any track
  o.edits.shots = {Shot(2)};
  EXPECT_NO_THROW(CheckEditsForPath(MakeFilm(), o));
  // A path without a shot column is shot 0.
  o.edits.shots = {Shot(0)};
  EXPECT_NO_THROW(MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o));
  o.edits.shots = {Shot(1)};
  EXPECT_THROW(MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o), Error);
  // A gain the parser would refuse, set in code, is refused too.
  ShotEdit nan = Shot(0);
  nan.gain = std::nan("");
  o.edits.shots = {nan};
  EXPECT_THROW(MakeHapticTrack(MakeEffectPath(CameraEffect::kTraveling), o), Error);
}

}  // namespace
}  // namespace hapcine
