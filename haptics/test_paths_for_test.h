#pragma once
// Test-only: camera paths like the paper's seven clips (section 4.1): 1 s
// still, 5 s of continuous motion, 1 s still, built with the core types.
// Positions in metres with the subject 4 m in front of the first camera
// (metadata subject_distance_m=4). Header-only so it stays out of the library.

#include <algorithm>
#include <cmath>
#include <random>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "core/rotation.h"
#include "haptics/semantic_model.h"

namespace hapcine::testing {

constexpr double kSubjectDistanceM = 4.0;

struct EffectPathSpec {
  CameraEffect effect = CameraEffect::kNone;
  double amount = 1.0;  // multiplies the default size of the motion (sign reverses)
  double fps = 30;
  double still_s = 1.0;  // before and after
  double motion_s = 5.0;
  double noise = 0.0;  // std of white noise on position (m) and angles (deg * 10)
  uint64_t seed = 7;
};

// Ease-in-out progress of the motion at time t.
inline double Progress(const EffectPathSpec& s, double t) {
  const double u = std::clamp((t - s.still_s) / s.motion_s, 0.0, 1.0);
  return 0.5 - 0.5 * std::cos(kPi * u);
}

inline CameraPath MakeEffectPath(const EffectPathSpec& s) {
  CameraPath path;
  path.metadata["fps"] = std::to_string(s.fps);
  path.metadata["subject_distance_m"] = "4";
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int n = static_cast<int>(std::lround((2 * s.still_s + s.motion_s) * s.fps)) + 1;
  const double D = kSubjectDistanceM;
  const double a = s.amount;
  for (int i = 0; i < n; ++i) {
    const double t = i / s.fps;
    const double p = Progress(s, t);
    CameraFrame f;
    f.frame = i;
    f.time_s = t;
    f.fov_deg = 50;
    PanTiltRoll ptr;
    switch (s.effect) {
      case CameraEffect::kNone:
        break;
      case CameraEffect::kCraneShot:
        f.center.y() = 2.0 * a * p;
        ptr.tilt_deg = -10.0 * a * p;
        break;
      case CameraEffect::kDutchAngle:
        ptr.roll_deg = 20.0 * a * p;
        break;
      case CameraEffect::kArcing: {
        const double alpha = DegToRad(30.0 * a * p);
        f.center = Eigen::Vector3d(D * std::sin(alpha), 0, -(D - D * std::cos(alpha)));
        ptr.pan_deg = RadToDeg(alpha);
        break;
      }
      case CameraEffect::kTraveling:
        f.center.x() = 2.0 * a * p;
        break;
      case CameraEffect::kTilting:
        ptr.tilt_deg = 25.0 * a * p;
        break;
      case CameraEffect::kZoomIn: {
        // Narrow the FOV from 50 deg by a factor (1 + a * p) in tan(fov/2);
        // a < 0 widens it by the same factor (a zoom-out).
        const double t0 = std::tan(DegToRad(50.0) / 2);
        const double factor = 1 + std::abs(a) * p;
        f.fov_deg = 2 * RadToDeg(std::atan(a >= 0 ? t0 / factor : t0 * factor));
        break;
      }
      case CameraEffect::kVertigo: {
        // Forward by d, FOV widened so the subject at D keeps its size.
        const double d = 2.0 * a * p;
        f.center.z() = -d;
        const double t0 = std::tan(DegToRad(40.0) / 2);
        f.fov_deg = 2 * RadToDeg(std::atan(t0 * D / (D - d)));
        break;
      }
    }
    if (s.noise > 0) {
      f.center += s.noise * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      ptr.pan_deg += 10 * s.noise * noise(rng);
      ptr.tilt_deg += 10 * s.noise * noise(rng);
      ptr.roll_deg += 10 * s.noise * noise(rng);
      f.fov_deg *= 1 + 0.1 * s.noise * noise(rng);
    }
    f.world_from_cam = QuaternionFromPanTiltRoll(ptr);
    path.frames.push_back(f);
  }
  return path;
}

inline CameraPath MakeEffectPath(CameraEffect e, double amount = 1.0) {
  EffectPathSpec s;
  s.effect = e;
  s.amount = amount;
  return MakeEffectPath(s);
}

// The same path seen from another world frame (ground truth may use any).
inline CameraPath TransformWorld(const CameraPath& in, const Eigen::Quaterniond& q,
                                 const Eigen::Vector3d& t) {
  CameraPath out = in;
  for (auto& f : out.frames) {
    f.center = q * f.center + t;
    f.world_from_cam = CanonicalQuaternion(q * f.world_from_cam);
  }
  return out;
}

// Largest |coordinate| of any actuator over a track, metres.
inline double MaxCoord(const HapticTrack& t) {
  double m = 0;
  for (const auto& s : t.samples)
    for (const auto& a : s.pos_m) m = std::max(m, a.cwiseAbs().maxCoeff());
  return m;
}

// Largest change of any coordinate from one sample to the next, metres.
inline double MaxStep(const HapticTrack& t) {
  double m = 0;
  for (size_t i = 1; i < t.samples.size(); ++i) {
    for (int a = 0; a < kNumActuators; ++a) {
      m = std::max(m, (t.samples[i].pos_m[a] - t.samples[i - 1].pos_m[a]).cwiseAbs().maxCoeff());
    }
  }
  return m;
}

}  // namespace hapcine::testing
