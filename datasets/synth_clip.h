#pragma once
// `hapcine synth`: renders a synthetic clip and writes its exact ground truth.
//
// For a preset (synth_presets.h) and options, SynthClip writes
//   <out_dir>/<preset>.mp4         H.264, yuv420p, frame k at pts time k / fps
//   <out_dir>/<preset>.camera.csv  the camera of every frame (camera-path.md),
//                                  time_s = k / fps, with focal_px, shot, model
// Both files appear only when both are complete (temporary names, then
// rename). docs/synth.md describes the scene, presets and conventions.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "datasets/render.h"
#include "datasets/synth_presets.h"

namespace hapcine {

struct SynthOptions {
  int width = 1280;           // pixels, even
  int height = 720;           // pixels, even
  double fps = 24;            // frames per second
  double duration_s = 7;      // clip length; the paper's "1 s" still parts scale as duration / 7
  int supersample = 2;        // N x N sub-samples on geometry edges (1 = off)
  bool adaptive = true;       // supersample only at geometry edges (textures are prefiltered)
  int jobs = 0;               // render threads (0 = all cores)
  uint32_t seed = 1;          // scene textures, handheld jitter, sensor noise
  int crf = 18;               // x264 CRF for clean presets
  int noisy_crf = 38;         // x264 CRF for the noise_compression preset
  std::string x264_preset = "fast";  // x264 speed preset
  double shutter = 0.5;       // exposure / frame interval for motion-blurred presets (180 deg)
  // Radial lens distortion k1 (render.h, DistortNormalised); used when
  // has_distortion, else 0 (or the variant's own).
  bool has_distortion = false;
  double distortion_k1 = 0;
  // "" = the presets as documented; "test" = the test-split look (other
  // textures and lighting, grain, motion blur, compression, vignetting, lens
  // distortion, far walkers) over the same camera paths (docs/synth.md).
  std::string variant;
  // Parts of the variant's look left out, to measure one factor at a time
  // (kVariantFactors: textures, lighting, grade, vignette, grain, blur,
  // compression, walkers); empty = the whole look.
  std::vector<std::string> variant_without;
  // Called after every frame with (preset, frames done, frames total).
  std::function<void(const std::string&, int, int)> progress;

  void Check() const;  // throws UsageError
};

struct SynthResult {
  std::string video_path;
  std::string camera_path;
  int frames = 0;
  int rendered_views = 0;  // ray-cast images (still frames reuse, motion blur adds)
};

// Every preset name: the seven Table 1 effects in the paper's order, then the
// hard cases.
std::vector<std::string> SynthPresetNames();
std::vector<std::string> SynthTable1PresetNames();
std::vector<std::string> SynthHardPresetNames();
// The presets with independently moving objects (not part of SynthPresetNames()).
std::vector<std::string> SynthMoverPresetNames();
// The names variant_without accepts.
const std::vector<std::string>& VariantFactorNames();
// One-line description of a preset (throws UsageError for unknown names).
std::string SynthPresetDescription(const std::string& preset);

// The ground truth of a preset without rendering anything: exactly what
// SynthClip writes to the CSV.
CameraPath SynthGroundTruth(const std::string& preset, const SynthOptions& options);

// Renders, encodes and writes one clip. Creates out_dir if needed. Throws
// UsageError on bad options/preset, hapcine::Error on I/O failure (and then
// leaves no output file behind).
SynthResult SynthClip(const std::string& preset, const SynthOptions& options,
                      const std::string& out_dir);

// The hall scene for a seed and style, built once per process and shared.
std::shared_ptr<const synth::Scene> SynthScene(uint32_t seed, synth::SceneStyle style,
                                               int threads = 0);

// The camera view for a camera state at the options' frame size.
synth::CameraView SynthView(const synth::CameraState& state, int width, int height);

}  // namespace hapcine
