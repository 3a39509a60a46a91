#include "datasets/synth_presets.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine::synth {
namespace {

using Eigen::Vector3d;

// Where most presets stand: 4.7 m in front of the characters at eye height.
const Vector3d kBaseCenter(0.0, 1.6, 0.6);
constexpr double kBaseFovDeg = 50;

double Ease(double t, double t0, double t1) {
  if (t <= t0) return 0;
  if (t >= t1) return 1;
  return 0.5 * (1 - std::cos(kPi * (t - t0) / (t1 - t0)));
}

double Mix(double a, double b, double s) { return a + (b - a) * s; }

// A camera at `center` looking at the characters.
CameraState Framing(const Vector3d& center, double fov_deg) {
  CameraState c;
  c.center = center;
  c.fov_deg = fov_deg;
  LookAt(center, HallSubjectCenter(), &c.pan_deg, &c.tilt_deg);
  return c;
}

// Smooth pseudo-random jitter in [-1, 1]-ish: three sinusoids with seeded
// frequencies and phases (low, mid, high band), the higher bands weaker.
double Jitter(double t, uint32_t seed, int channel) {
  static const double kLo[] = {0.3, 1.5, 4.0}, kHi[] = {1.5, 4.0, 8.0}, kAmp[] = {1.0, 0.4, 0.15};
  double v = 0;
  for (int k = 0; k < 3; ++k) {
    const double f = Mix(kLo[k], kHi[k], Hash01(channel, 2 * k, seed));
    const double phase = 2 * kPi * Hash01(channel, 2 * k + 1, seed);
    v += kAmp[k] * std::sin(2 * kPi * f * t + phase);
  }
  return v / 1.55;
}

// Dolly zoom: the subject plane keeps its width in the image, so
// d * tan(fov / 2) is constant.
CameraState DollyZoom(double s, double d0, double d1, double fov0_deg) {
  const Vector3d subject = HallSubjectCenter();
  const double d = Mix(d0, d1, s);
  CameraState c;
  c.center = Vector3d(subject.x(), subject.y(), subject.z() + d);
  c.fov_deg = RadToDeg(2 * std::atan(d0 * std::tan(DegToRad(fov0_deg) / 2) / d));
  return c;  // pan = tilt = roll = 0: the subject plane stays put
}

}  // namespace

Eigen::Quaterniond CameraState::world_from_cam() const {
  return QuaternionFromPanTiltRoll({pan_deg, tilt_deg, roll_deg});
}

void LookAt(const Vector3d& center, const Vector3d& target, double* pan_deg, double* tilt_deg) {
  const Vector3d v = target - center;
  // Forward of R_y(pan) R_x(tilt) is (-sin pan cos tilt, sin tilt, -cos pan cos tilt).
  *pan_deg = RadToDeg(std::atan2(-v.x(), -v.z()));
  *tilt_deg = RadToDeg(std::atan2(v.y(), std::hypot(v.x(), v.z())));
}

int ClipTiming::frames() const { return static_cast<int>(std::lround(duration_s * fps)); }
double ClipTiming::FrameTime(int frame) const { return frame / fps; }

const std::vector<PresetInfo>& SynthPresets() {
  static const std::vector<PresetInfo> kPresets = [] {
    std::vector<PresetInfo> p;
    auto add = [&p](const char* name, const char* group, const char* desc) -> PresetInfo& {
      PresetInfo i;
      i.name = name;
      i.group = group;
      i.description = desc;
      p.push_back(i);
      return p.back();
    };
    add("crane_shot", "table1",
        "crane up y 1.5 -> 4.3 m while tilting down to keep the characters framed (y, tilt)");
    add("dutch_angle", "table1", "roll 0 -> 20 deg from a fixed position (roll)");
    add("arcing", "table1",
        "70 deg arc of radius 4.6 m around the characters, panning to face them (x, z, pan)");
    add("traveling", "table1", "lateral move x -2 -> +2 m, view direction fixed (x)");
    add("tilting", "table1",
        "low camera (0.45 m) tilts up -18 -> +14 deg, ending in a low angle (tilt)");
    add("zoom_in", "table1", "horizontal fov 60 -> 30 deg from a fixed position (fov)");
    add("vertigo", "table1",
        "dolly zoom: forward 7 -> 3 m from the characters, fov 30 -> 64 deg (z, fov)");
    add("slow_pan", "hard", "pan 0 -> 6 deg over 5 s (about one pixel per frame)");
    add("whip_pan", "hard", "80 deg pan in 0.75 s with motion blur (180 deg shutter)")
        .motion_blur = true;
    add("handheld_shake", "hard",
        "static framing with seeded handheld jitter (~0.5 deg, ~1.5 cm) all the time");
    add("telephoto_zoom_pan", "hard", "narrow fov 15 -> 10 deg zoom with a 4 deg pan");
    add("dolly_zoom_parallax", "hard",
        "strong dolly zoom: forward 8 -> 2 m, fov 20 -> 70 deg (large parallax)");
    add("low_texture", "hard", "pan 0 -> 20 deg in a flat, weakly textured hall")
        .scene = SceneStyle::kLowTexture;
    {
      PresetInfo& i = add("noise_compression", "hard",
                          "the traveling move with sensor noise (sigma 6) and heavy H.264 (high CRF)");
      i.noise_sigma = 6;
      i.high_crf = true;
    }
    add("hard_cut", "hard",
        "shot 0 pans 8 deg; cut at mid-clip to shot 1, a side camera moving sideways")
        .cut = true;
    add("fade_to_black", "hard",
        "pan 0 -> 25 deg while the picture fades to black (2.5-3.5 s) and back (4-5 s)")
        .fade = true;
    add("static_camera", "hard", "camera never moves");
    return p;
  }();
  return kPresets;
}

const std::vector<PresetInfo>& SynthMoverPresets() {
  static const std::vector<PresetInfo> kPresets = [] {
    std::vector<PresetInfo> p;
    auto add = [&p](const char* name, MoverKind kind, const char* desc) -> PresetInfo& {
      PresetInfo i;
      i.name = name;
      i.group = "movers";
      i.description = desc;
      i.movers = kind;
      p.push_back(i);
      return p.back();
    };
    add("head_turn", MoverKind::kHead,
        "static camera on a head and shoulders (~60 % of the frame height) that turns, nods, "
        "blinks and talks");
    add("head_turn_dark", MoverKind::kHead,
        "head_turn in a dark, weakly textured hall: the background gives few tracks")
        .scene = SceneStyle::kDarkLowTexture;
    add("head_push_in", MoverKind::kHead,
        "the head_turn scene with a slow 0.2 m push-in (view direction fixed)");
    add("pan_crossing", MoverKind::kCrossing,
        "pan 0 -> 30 deg while three people-sized walkers cross 1.5-4 m in front");
    add("traveling_crossing", MoverKind::kCrossing,
        "the traveling move (x -2 -> +2 m) while three walkers cross in front");
    add("crowd_static", MoverKind::kCrowd,
        "static camera; a crowd of fourteen walkers 3-9 m away, mostly walking across");
    return p;
  }();
  return kPresets;
}

std::string MoverKindName(MoverKind kind) {
  switch (kind) {
    case MoverKind::kHead: return "head";
    case MoverKind::kCrossing: return "crossing";
    case MoverKind::kCrowd: return "crowd";
    case MoverKind::kFarWalkers: return "far_walkers";
    case MoverKind::kNone: break;
  }
  return "none";
}

const PresetInfo& FindSynthPreset(const std::string& name) {
  std::string names;
  for (const auto* list : {&SynthPresets(), &SynthMoverPresets()}) {
    for (const PresetInfo& p : *list) {
      if (p.name == name) return p;
      names += (names.empty() ? "" : ", ") + p.name;
    }
  }
  throw UsageError("unknown preset '" + name + "' (known: " + names + ")");
}

int PresetCutFrame(const PresetInfo& preset, const ClipTiming& timing) {
  return preset.cut ? timing.frames() / 2 : -1;
}

double PresetBrightnessAt(const PresetInfo& preset, double t, const ClipTiming& timing) {
  if (!preset.fade) return 1;
  const double u = timing.unit_s();
  if (t <= 2.5 * u || t >= 5.0 * u) return 1;
  if (t < 3.5 * u) return 1 - (t - 2.5 * u) / u;  // fade out over 1 s
  if (t <= 4.0 * u) return 0;                      // black for 0.5 s
  return (t - 4.0 * u) / u;                         // fade in over 1 s
}

CameraState PresetCameraAt(const PresetInfo& preset, double t, const ClipTiming& timing,
                           uint32_t seed) {
  const double u = timing.unit_s();
  const double s = Ease(t, u, 6 * u);  // the Table 1 move: still 1 s, move 5 s, still 1 s
  const Vector3d subject = HallSubjectCenter();
  const std::string& n = preset.name;
  CameraState c = Framing(kBaseCenter, kBaseFovDeg);
  if (n == "crane_shot") {
    c.center = Vector3d(0, Mix(1.5, 4.3, s), 0.9);
    c.pan_deg = 0;  // pan stays 0, so aim in the camera's vertical plane
    c.tilt_deg = RadToDeg(std::atan2(subject.y() - c.center.y(), c.center.z() - subject.z()));
  } else if (n == "dutch_angle") {
    c.pan_deg = 0;
    c.roll_deg = Mix(0, 20, s);
  } else if (n == "arcing") {
    const double radius = 4.6, a = DegToRad(Mix(-35, 35, s));
    c.center = Vector3d(subject.x() + radius * std::sin(a), 1.6, subject.z() + radius * std::cos(a));
    c.pan_deg = RadToDeg(a);
    c.tilt_deg = RadToDeg(std::atan2(subject.y() - 1.6, radius));
  } else if (n == "traveling" || n == "noise_compression") {
    c.pan_deg = 0;
    c.center.x() = Mix(-2, 2, s);
  } else if (n == "tilting") {
    c.center = Vector3d(0, 0.45, 0.6);
    c.pan_deg = 0;
    c.tilt_deg = Mix(-18, 14, s);
  } else if (n == "zoom_in") {
    c.pan_deg = 0;
    c.fov_deg = Mix(60, 30, s);
  } else if (n == "vertigo") {
    c = DollyZoom(s, 7.0, 3.0, 30);
  } else if (n == "slow_pan") {
    c.pan_deg += Mix(0, 6, s);
  } else if (n == "whip_pan") {
    c.pan_deg += Mix(0, 80, Ease(t, 3 * u, 3.75 * u));
  } else if (n == "handheld_shake") {
    c.fov_deg = 45;
    c.pan_deg += 0.5 * Jitter(t, seed, 0);
    c.tilt_deg += 0.4 * Jitter(t, seed, 1);
    c.roll_deg += 0.3 * Jitter(t, seed, 2);
    c.center += Vector3d(0.015 * Jitter(t, seed, 3), 0.012 * Jitter(t, seed, 4),
                         0.008 * Jitter(t, seed, 5));
  } else if (n == "telephoto_zoom_pan") {
    c.fov_deg = Mix(15, 10, s);
    c.pan_deg += Mix(-2, 2, s);
  } else if (n == "dolly_zoom_parallax") {
    c = DollyZoom(s, 8.0, 2.0, 20);
  } else if (n == "low_texture") {
    c.pan_deg += Mix(0, 20, s);
  } else if (n == "hard_cut") {
    const int cut = PresetCutFrame(preset, timing);
    const double t_cut = timing.FrameTime(cut);
    if (t < t_cut - 1e-9) {
      c.pan_deg += Mix(0, 8, Ease(t, u, t_cut));
    } else {
      // Shot 1: a different camera, higher and to the right, trucking left.
      c = Framing(Vector3d(3.0, 2.2, 0.5), 40);
      c.center.x() = Mix(3.0, 1.0, Ease(t, t_cut, 6 * u));
      c.shot = 1;
    }
  } else if (n == "fade_to_black") {
    c.pan_deg += Mix(0, 25, s);
  } else if (n == "static_camera" || n == "crowd_static") {
    // Framing only.
  } else if (n == "head_turn" || n == "head_turn_dark" || n == "head_push_in") {
    // Frame the head slightly left of centre, as in a dialogue close-up.
    LookAt(c.center, MoverHeadCenter() + Vector3d(-0.05, -0.02, 0), &c.pan_deg, &c.tilt_deg);
    if (n == "head_push_in") c.center.z() -= Mix(0, 0.2, s);  // view direction fixed
  } else if (n == "pan_crossing") {
    c.pan_deg += Mix(0, 30, s);
  } else if (n == "traveling_crossing") {
    c.pan_deg = 0;
    c.center.x() = Mix(-2, 2, s);
  } else {
    throw UsageError("no camera motion for preset '" + n + "'");
  }
  return c;
}

std::string MotionClass(const CameraState& a, const CameraState& b) {
  const bool moved = (a.center - b.center).norm() > 1e-9;
  const bool turned = AngleBetweenDeg(a.world_from_cam(), b.world_from_cam()) > 1e-7;
  const bool zoomed = std::abs(a.fov_deg - b.fov_deg) > 1e-9;
  if (moved) return zoomed ? "general+zoom" : "general";
  if (turned && zoomed) return "rotation+zoom";
  if (turned) return "rotation";
  if (zoomed) return "zoom";
  return "static";
}

}  // namespace hapcine::synth
