#pragma once
// Camera motions of the synthetic clips: the seven camera effects of the
// paper's Table 1 (section 4.1: still for 1 s, a continuous effect for 5 s,
// still for 1 s, at 24 fps) and a set of hard cases for the estimator.
// Every preset is an exact, closed-form function of time, so the ground truth
// written next to the video is the very camera that rendered each frame.
//
// Timings scale with the clip duration T: "1 s" is T/7, so a 7 s clip follows
// the paper exactly and a short test clip keeps the same shape. Motion uses a
// cosine ease, (1 - cos(pi u)) / 2, so velocity is continuous (zero at both
// ends of the move). Angles follow core/rotation.h: world_from_cam =
// R_y(pan) R_x(tilt) R_z(roll); positive pan looks left, positive tilt up,
// positive roll turns the camera counter-clockwise.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "datasets/movers.h"
#include "datasets/scene_hall.h"

namespace hapcine::synth {

// The paper's camera parameters C = [x, y, z, phi (tilt), theta (pan),
// psi (roll), gamma (fov)] plus the shot index.
struct CameraState {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // metres
  double pan_deg = 0, tilt_deg = 0, roll_deg = 0;
  double fov_deg = 50;  // horizontal
  int shot = 0;

  Eigen::Quaterniond world_from_cam() const;
};

struct PresetInfo {
  std::string name;
  std::string group;        // "table1", "hard" or "movers"
  std::string description;  // one line, for --list and docs
  SceneStyle scene = SceneStyle::kTextured;
  bool motion_blur = false;  // average sub-frame renders over the shutter interval
  float noise_sigma = 0;     // Gaussian sensor noise, 8-bit levels
  bool high_crf = false;     // encode with SynthOptions::noisy_crf
  bool fade = false;         // brightness follows PresetBrightnessAt
  bool cut = false;          // two shots; PresetCutFrame gives the first frame of shot 1
  MoverKind movers = MoverKind::kNone;  // independently moving objects (not in the ground truth)
};

// All presets: Table 1 in the paper's order, then the hard cases (`--all`).
const std::vector<PresetInfo>& SynthPresets();
// The presets with independently moving objects (`--movers`), kept apart so
// that `--all` stays the 17 presets above.
const std::vector<PresetInfo>& SynthMoverPresets();
// Name of a mover kind for the metadata ("head", "crossing", "crowd", "far_walkers").
std::string MoverKindName(MoverKind kind);
// Throws UsageError naming the valid presets (searches both lists).
const PresetInfo& FindSynthPreset(const std::string& name);

struct ClipTiming {
  double duration_s = 7;
  double fps = 24;
  int frames() const;                  // round(duration * fps)
  double FrameTime(int frame) const;   // frame / fps
  double unit_s() const { return duration_s / 7; }  // the paper's "1 s"
};

// Camera of `preset` at time t_s (exact, any t, e.g. within a shutter interval).
CameraState PresetCameraAt(const PresetInfo& preset, double t_s, const ClipTiming& timing,
                           uint32_t seed);
// Picture brightness multiplier in [0, 1] at t_s (fades); 1 for most presets.
double PresetBrightnessAt(const PresetInfo& preset, double t_s, const ClipTiming& timing);
// First frame of the second shot for presets with a cut, else -1.
int PresetCutFrame(const PresetInfo& preset, const ClipTiming& timing);

// Motion class between two camera states, as the estimator's model names:
// "static", "zoom", "rotation", "rotation+zoom", "general" (any translation at a
// constant focal) or "general+zoom" (translation and a focal change: a dolly zoom).
std::string MotionClass(const CameraState& a, const CameraState& b);

// Pan and tilt (degrees) that point the camera at `center` towards `target`.
void LookAt(const Eigen::Vector3d& center, const Eigen::Vector3d& target, double* pan_deg,
            double* tilt_deg);

}  // namespace hapcine::synth
