#include "datasets/synth_clip.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "core/output_files.h"
#include "core/rotation.h"
#include "datasets/video_writer.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;
using synth::CameraState;
using synth::CameraView;
using synth::PresetInfo;

synth::ClipTiming Timing(const SynthOptions& o) { return {o.duration_s, o.fps}; }

std::string Num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// The look of a clip: the preset's own, or the test-split variant's
// (docs/synth.md, "Test-split variant"). Only appearance changes; the camera
// path is the preset's.
struct Look {
  uint32_t scene_seed = 1;
  double k1 = 0;
  synth::MoverKind movers = synth::MoverKind::kNone;
  bool variant = false;
  bool lighting = false, grade = false, vignette = false, grain = false;  // the variant's treatment
  int max_blur_views = 48;  // sub-frames of a motion-blurred frame at most
  bool blur = false;        // average sub-frames over the shutter
  int crf = 18;
};

constexpr uint32_t kVariantSeedOffset = 1000003;  // other textures, posters, mover clothes
constexpr double kVariantK1 = -0.04;               // mild barrel distortion
constexpr int kVariantCrf = 26;                    // visible compression
constexpr float kVariantGrainSigma = 3.0f;         // film grain, 8-bit levels
constexpr float kVariantVignette = 0.3f;           // light fall-off at the corners
constexpr int kVariantBlurViews = 4;               // bounded cost of the variant's motion blur

// Is this part of the variant's look in the clip (the variant, not left out)?
bool VariantHas(const SynthOptions& o, const std::string& factor) {
  const auto& w = o.variant_without;
  return o.variant == "test" && std::find(w.begin(), w.end(), factor) == w.end();
}

Look ClipLook(const PresetInfo& p, const SynthOptions& o) {
  Look look;
  look.variant = o.variant == "test";
  look.scene_seed = VariantHas(o, "textures") ? o.seed + kVariantSeedOffset : o.seed;
  look.lighting = VariantHas(o, "lighting");
  look.grade = VariantHas(o, "grade");
  look.vignette = VariantHas(o, "vignette");
  look.grain = VariantHas(o, "grain");
  look.movers = p.movers;
  if (VariantHas(o, "walkers") && look.movers == synth::MoverKind::kNone) {
    look.movers = synth::MoverKind::kFarWalkers;
  }
  look.k1 = o.has_distortion ? o.distortion_k1 : look.variant ? kVariantK1 : 0;
  look.blur = p.motion_blur || VariantHas(o, "blur");
  look.max_blur_views = p.motion_blur ? 48 : kVariantBlurViews;
  look.crf = p.high_crf ? o.noisy_crf : VariantHas(o, "compression") ? std::max(o.crf, kVariantCrf) : o.crf;
  return look;
}

CameraView ClipView(const PresetInfo& p, double t, const SynthOptions& o, const Look& look) {
  CameraView v = SynthView(PresetCameraAt(p, t, Timing(o), o.seed), o.width, o.height);
  v.k1 = look.k1;
  if (look.movers != synth::MoverKind::kNone) {
    v.movers = std::make_shared<const synth::MoverFrame>(
        synth::MoversAt(look.movers, t, o.duration_s, look.scene_seed));
  }
  return v;
}

// Views averaged into frame `frame`: one at the frame time, or, for
// motion-blurred presets, enough sub-frame views across the shutter interval
// (centred on the frame time) that consecutive ones move the image by at most
// ~2.5 px. The ground truth is the pose at the centre of the exposure. The
// exposure stays inside the frame's shot (an edit joins whole frames: a
// shutter never opens on one take and closes on the next), so the first
// frame of a shot is exposed from its own time on.
std::vector<CameraView> FrameViews(const PresetInfo& p, int frame, const SynthOptions& o,
                                   const Look& look) {
  const synth::ClipTiming timing = Timing(o);
  const double t = timing.FrameTime(frame);
  if (!look.blur) return {ClipView(p, t, o, look)};
  const int shot = PresetCameraAt(p, t, timing, o.seed).shot;
  double open = t - 0.5 * o.shutter / o.fps, close = t + 0.5 * o.shutter / o.fps;
  if (PresetCameraAt(p, open, timing, o.seed).shot != shot) open = t;
  if (PresetCameraAt(p, close, timing, o.seed).shot != shot) close = t;
  const CameraState a = PresetCameraAt(p, open, timing, o.seed);
  const CameraState b = PresetCameraAt(p, close, timing, o.seed);
  const double f = FocalPxFromFovDeg(std::max(a.fov_deg, b.fov_deg), o.width);
  const double disp_px = DegToRad(AngleBetweenDeg(a.world_from_cam(), b.world_from_cam())) * f +
                         std::abs(FocalPxFromFovDeg(a.fov_deg, o.width) -
                                  FocalPxFromFovDeg(b.fov_deg, o.width)) +
                         (a.center - b.center).norm() * f;  // worst case: 1 m depth
  const int n = std::clamp(static_cast<int>(std::ceil(disp_px / 2.5)), 1, look.max_blur_views);
  std::vector<CameraView> views;
  for (int k = 0; k < n; ++k) {
    const double tk = n == 1 ? t : open + (k + 0.5) / n * (close - open);
    views.push_back(ClipView(p, tk, o, look));
  }
  return views;
}

bool SameViews(const std::vector<CameraView>& a, const std::vector<CameraView>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].center != b[i].center || a[i].fov_deg != b[i].fov_deg ||
        a[i].world_from_cam.coeffs() != b[i].world_from_cam.coeffs() || a[i].k1 != b[i].k1 ||
        a[i].movers || b[i].movers) {  // movers move: every frame is rendered
      return false;
    }
  }
  return true;
}

void PrepareOutputDir(const std::string& dir) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw Error(dir, "output path exists and is not a directory");
    return;
  }
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir, "cannot create output directory: " + ec.message());
}

}  // namespace

void SynthOptions::Check() const {
  if (width < 16 || height < 16 || width % 2 || height % 2 || width > 7680 || height > 4320) {
    throw UsageError("width and height must be even and in [16, 7680] x [16, 4320]");
  }
  if (!(fps >= 1 && fps <= 240)) throw UsageError("fps must be in [1, 240]");
  if (!(duration_s > 0 && duration_s <= 600)) throw UsageError("duration must be in (0, 600] s");
  if (std::lround(duration_s * fps) < 2) throw UsageError("a clip needs at least 2 frames");
  if (supersample < 1 || supersample > 8) throw UsageError("supersample must be in [1, 8]");
  if (jobs < 0 || jobs > 1024) throw UsageError("jobs must be in [0, 1024]");
  if (crf < 0 || crf > 51 || noisy_crf < 0 || noisy_crf > 51) {
    throw UsageError("crf must be in [0, 51]");
  }
  if (!(shutter > 0 && shutter <= 1)) throw UsageError("shutter must be in (0, 1]");
  if (variant != "" && variant != "test") {
    throw UsageError("unknown variant '" + variant + "' (known: test)");
  }
  for (const std::string& f : variant_without) {
    const auto& known = VariantFactorNames();
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      throw UsageError("unknown variant factor '" + f + "' (see --help)");
    }
  }
  if (!variant_without.empty() && variant != "test") {
    throw UsageError("--variant-without needs --variant test");
  }
  if (has_distortion && !(distortion_k1 >= -0.2 && distortion_k1 <= 0.2)) {
    throw UsageError("distortion k1 must be in [-0.2, 0.2]");
  }
  static const char* kX264[] = {"ultrafast", "superfast", "veryfast", "faster", "fast",
                                "medium",    "slow",      "slower",   "veryslow", "placebo"};
  if (std::find(std::begin(kX264), std::end(kX264), x264_preset) == std::end(kX264)) {
    throw UsageError("unknown x264 preset '" + x264_preset + "'");
  }
}

const std::vector<std::string>& VariantFactorNames() {
  static const std::vector<std::string> names = {"textures", "lighting", "grade",       "vignette",
                                                 "grain",    "blur",     "compression", "walkers"};
  return names;
}

std::vector<std::string> SynthPresetNames() {
  std::vector<std::string> out;
  for (const PresetInfo& p : synth::SynthPresets()) out.push_back(p.name);
  return out;
}

std::vector<std::string> SynthTable1PresetNames() {
  std::vector<std::string> out;
  for (const PresetInfo& p : synth::SynthPresets()) {
    if (p.group == "table1") out.push_back(p.name);
  }
  return out;
}

std::vector<std::string> SynthHardPresetNames() {
  std::vector<std::string> out;
  for (const PresetInfo& p : synth::SynthPresets()) {
    if (p.group == "hard") out.push_back(p.name);
  }
  return out;
}

std::vector<std::string> SynthMoverPresetNames() {
  std::vector<std::string> out;
  for (const PresetInfo& p : synth::SynthMoverPresets()) out.push_back(p.name);
  return out;
}

std::string SynthPresetDescription(const std::string& preset) {
  return synth::FindSynthPreset(preset).description;
}

CameraView SynthView(const CameraState& state, int width, int height) {
  CameraView v;
  v.center = state.center;
  v.world_from_cam = state.world_from_cam();
  v.fov_deg = state.fov_deg;
  v.width = width;
  v.height = height;
  return v;
}

CameraPath SynthGroundTruth(const std::string& preset, const SynthOptions& options) {
  options.Check();
  const PresetInfo& p = synth::FindSynthPreset(preset);
  const synth::ClipTiming timing = Timing(options);
  const int n = timing.frames();
  std::vector<CameraState> states(n);
  for (int i = 0; i < n; ++i) {
    states[i] = PresetCameraAt(p, timing.FrameTime(i), timing, options.seed);
  }
  CameraPath path;
  auto& m = path.metadata;
  m["width"] = std::to_string(options.width);
  m["height"] = std::to_string(options.height);
  m["fps"] = Num(options.fps);
  m["preset"] = p.name;
  m["generator"] = "hapcine synth";
  m["seed"] = std::to_string(options.seed);
  m["duration_s"] = Num(options.duration_s);
  m["frames"] = std::to_string(n);
  m["units"] = "m";
  m["scene"] = p.scene == synth::SceneStyle::kLowTexture       ? "hall_low_texture"
               : p.scene == synth::SceneStyle::kDarkLowTexture ? "hall_dark_low_texture"
                                                               : "hall";
  m["pixel_centre"] = "i+0.5";  // pixel (i, j) centre at (i+0.5, j+0.5); principal point W/2 H/2
  const Look look = ClipLook(p, options);
  if (look.blur) m["shutter"] = Num(options.shutter);
  if (look.variant) {
    m["variant"] = options.variant;
    m["scene_seed"] = std::to_string(look.scene_seed);
    m["grain_sigma"] = Num(look.grain ? kVariantGrainSigma : 0.0f);
    m["vignette"] = Num(look.vignette ? kVariantVignette : 0.0f);
    m["crf"] = std::to_string(look.crf);
    if (!options.variant_without.empty()) {
      std::string w;
      for (const std::string& f : options.variant_without) w += (w.empty() ? "" : " ") + f;
      m["variant_without"] = w;
    }
  }
  if (look.k1 != 0) m["distortion_k1"] = Num(look.k1);  // render.h DistortNormalised
  if (look.movers != synth::MoverKind::kNone) m["movers"] = synth::MoverKindName(look.movers);
  if (p.noise_sigma > 0) m["noise_sigma"] = Num(p.noise_sigma);
  if (p.cut) m["cut_frames"] = std::to_string(PresetCutFrame(p, timing));
  if (p.fade) {
    const double u = timing.unit_s();
    m["fade_out_s"] = Num(2.5 * u) + "-" + Num(3.5 * u);
    m["black_s"] = Num(3.5 * u) + "-" + Num(4.0 * u);
    m["fade_in_s"] = Num(4.0 * u) + "-" + Num(5.0 * u);
  }
  for (int i = 0; i < n; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = timing.FrameTime(i);
    f.center = states[i].center;
    f.world_from_cam = states[i].world_from_cam();
    f.fov_deg = states[i].fov_deg;
    f.focal_px = FocalPxFromFovDeg(states[i].fov_deg, options.width);
    f.shot = states[i].shot;
    // The model of a frame is the motion that brought the camera there from
    // the previous frame of the same shot (the first frame of a shot takes
    // the motion to the next one).
    int a = i - 1, b = i;
    if (a < 0 || states[a].shot != states[b].shot) {
      a = i;
      b = i + 1;
    }
    f.model = (b < n && states[a].shot == states[b].shot) ? synth::MotionClass(states[a], states[b])
                                                          : "static";
    path.frames.push_back(std::move(f));
  }
  return path;
}

std::shared_ptr<const synth::Scene> SynthScene(uint32_t seed, synth::SceneStyle style,
                                               int threads) {
  static std::mutex mutex;
  static std::map<std::pair<uint32_t, int>, std::shared_ptr<const synth::Scene>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(seed, static_cast<int>(style));
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  if (cache.size() >= 2) cache.clear();  // bounded memory: a few hundred MB at most
  auto scene = synth::BuildHallScene(seed, style, threads);
  cache[key] = scene;
  return scene;
}

// The test-split variant's lighting: the lights moved and warmer/cooler,
// a darker ambient term (same geometry and textures).
std::shared_ptr<const synth::Scene> VariantLighting(const synth::Scene& base) {
  auto lit = std::make_shared<synth::Scene>(base);
  lit->lights = {{Eigen::Vector3d(-5, 4.2, -1), 0.6f, 4.0},
                 {Eigen::Vector3d(4, 4.6, -6), 0.35f, 6.0},
                 {Eigen::Vector3d(1, 3.5, 3.0), 0.3f, 4.0}};
  lit->ambient = 0.33f;
  return lit;
}

// Per-pixel gain of the variant's vignetting: 1 - v (r / r_corner)^2.
cv::Mat VignetteGain(int width, int height) {
  cv::Mat gain(height, width, CV_32FC3);
  const double rc2 = 0.25 * (double(width) * width + double(height) * height);
  for (int y = 0; y < height; ++y) {
    float* row = gain.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      const double dx = x + 0.5 - 0.5 * width, dy = y + 0.5 - 0.5 * height;
      const float g = static_cast<float>(1 - kVariantVignette * (dx * dx + dy * dy) / rc2);
      row[3 * x] = row[3 * x + 1] = row[3 * x + 2] = g;
    }
  }
  return gain;
}

// The variant's picture treatment of a rendered frame (BGR, 0..255 floats):
// a warm grade with a slight gamma, vignetting, and luminance film grain
// seeded per frame.
void VariantTreatment(const Look& look, const cv::Mat& vignette, int frame, cv::Mat* img) {
  if (look.grade) cv::multiply(*img, cv::Scalar(0.9, 1.0, 1.08), *img);  // B, G, R gains
  if (look.vignette) cv::multiply(*img, vignette, *img);
  cv::max(*img, 0.0, *img);
  if (look.grade) {
    cv::pow(*img * (1.0 / 255), 0.9, *img);
    *img *= 255.0;
  }
  if (!look.grain) return;
  const uint32_t seed = look.scene_seed;
  cv::Mat grain(img->size(), CV_32FC1);
  cv::RNG rng((static_cast<uint64_t>(seed) << 32) ^ (0x85EBCA6BULL * (frame + 7)));
  rng.fill(grain, cv::RNG::NORMAL, 0, kVariantGrainSigma);
  cv::Mat grain3;
  cv::merge(std::vector<cv::Mat>{grain, grain, grain}, grain3);
  *img += grain3;
}

SynthResult SynthClip(const std::string& preset, const SynthOptions& options,
                      const std::string& out_dir) {
  options.Check();
  const PresetInfo& p = synth::FindSynthPreset(preset);
  const CameraPath truth = SynthGroundTruth(preset, options);
  const Look look = ClipLook(p, options);
  PrepareOutputDir(out_dir);
  SynthResult result;
  result.video_path = (fs::path(out_dir) / (p.name + ".mp4")).string();
  result.camera_path = (fs::path(out_dir) / (p.name + ".camera.csv")).string();
  result.frames = static_cast<int>(truth.frames.size());

  VideoWriterOptions vopt;
  vopt.crf = look.crf;
  vopt.preset = options.x264_preset;
  VideoWriter writer;
  writer.Open(result.video_path, options.width, options.height, options.fps, vopt);

  auto scene = SynthScene(look.scene_seed, p.scene, options.jobs);
  if (look.lighting) scene = VariantLighting(*scene);
  const cv::Mat vignette = look.vignette ? VignetteGain(options.width, options.height) : cv::Mat();
  synth::RenderOptions ropt;
  ropt.supersample = options.supersample;
  ropt.adaptive = options.adaptive;
  ropt.threads = options.jobs;
  synth::RenderOptions blur_opt = ropt;
  blur_opt.supersample = 1;  // averaging many sub-frames already antialiases

  const synth::ClipTiming timing = Timing(options);
  std::vector<CameraView> prev_views;
  cv::Mat clean, frame_f, frame_8u, noise;
  for (int i = 0; i < result.frames; ++i) {
    std::vector<CameraView> views = FrameViews(p, i, options, look);
    if (clean.empty() || !SameViews(views, prev_views)) {  // still frames are rendered once
      clean = views.size() == 1 ? synth::RenderView(*scene, views[0], ropt)
                                : synth::RenderAverage(*scene, views, blur_opt);
      result.rendered_views += static_cast<int>(views.size());
      prev_views = std::move(views);
    }
    const double gain = PresetBrightnessAt(p, timing.FrameTime(i), timing);
    frame_f = gain == 1.0 ? clean : clean * gain;
    if (look.variant) {
      if (frame_f.data == clean.data) frame_f = clean.clone();
      VariantTreatment(look, vignette, i, &frame_f);
    }
    if (p.noise_sigma > 0) {
      noise.create(frame_f.size(), CV_32FC3);
      cv::RNG rng((static_cast<uint64_t>(options.seed) << 32) ^ (0x9E3779B9ULL * (i + 1)));
      rng.fill(noise, cv::RNG::NORMAL, 0, p.noise_sigma);
      frame_f = frame_f + noise;
    }
    frame_f.convertTo(frame_8u, CV_8UC3);  // rounds and saturates
    writer.Write(frame_8u);
    if (options.progress) options.progress(p.name, i + 1, result.frames);
  }
  // The pair is committed together: complete, or absent.
  OutputSet pair({}, {});
  WriteCameraPathFile(truth, result.camera_path);
  writer.Close();
  pair.CommitAll();
  return result;
}

}  // namespace hapcine
