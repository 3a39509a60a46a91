// hapcine synth: render synthetic clips with exact ground-truth camera paths.
// A thin mapping of flags onto SynthOptions; the work is SynthClip() in
// datasets/synth_clip.h, documented in docs/synth.md.

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "datasets/synth_clip.h"

namespace hapcine::cli {

namespace {

// Everything the command line sets besides SynthOptions.
struct SynthArgs {
  std::vector<std::string> presets;
  std::string out_dir;
  bool all = false, table1 = false, hard = false, movers = false, list = false, full_ss = false;
  double distortion_k1 = 0;
  CLI::Option* distortion = nullptr;
};

void AddPresetOptions(CLI::App& app, SynthArgs* a, SynthOptions* opt) {
  app.add_option("presets", a->presets, "preset names (see --list)");
  app.add_flag("--all", a->all, "every preset (Table 1 and hard cases)");
  app.add_flag("--table1", a->table1, "the seven Table 1 presets");
  app.add_flag("--hard", a->hard, "the hard-case presets");
  app.add_flag("--movers", a->movers,
               "the presets with independently moving objects (a head, walkers, a crowd; not "
               "part of --all)");
  app.add_option("--variant", opt->variant,
                 "'test': the test-split look (other textures and lighting, grain, motion blur, "
                 "compression, vignetting, lens distortion, far walkers) over the same camera "
                 "paths");
  app.add_option("--variant-without", opt->variant_without,
                 "with --variant test: parts of its look left out, to measure one at a time: "
                 "textures, lighting, grade, vignette, grain, blur, compression, walkers")
      ->delimiter(',');
  a->distortion = app.add_option("--distortion", a->distortion_k1,
                                 "radial lens distortion k1: x_d = x_n (1 + k1 r_n^2), x_n = (x - "
                                 "W/2) / focal_px (OpenCV k1, COLMAP SIMPLE_RADIAL); < 0 = barrel")
                      ->check(FiniteRange(-0.2, 0.2));
  app.add_flag("--list", a->list, "print every preset with a one-line description and exit");
  app.add_option("-o,--output", a->out_dir, "output directory (created if missing)");
}

void AddRenderOptions(CLI::App& app, SynthArgs* a, SynthOptions* opt) {
  app.add_option("--width", opt->width, "frame width, pixels (even)")->capture_default_str()
      ->check(FiniteRange(16, 7680));
  app.add_option("--height", opt->height, "frame height, pixels (even)")->capture_default_str()
      ->check(FiniteRange(16, 4320));
  app.add_option("--fps", opt->fps, "frame rate")->capture_default_str()
      ->check(FiniteRange(1, 240));
  app.add_option("--duration-s", opt->duration_s,
                 "clip length, seconds; the still/move/still parts keep the 1:5:1 ratio")
      ->capture_default_str()
      ->check(FiniteRange(0, 600));
  app.add_option("--supersample", opt->supersample,
                 "N: N x N anti-aliasing sub-samples per pixel at geometry edges (1 = off; "
                 "textures are always prefiltered)")
      ->capture_default_str()
      ->check(FiniteRange(1, 8));
  app.add_flag("--full-supersample", a->full_ss,
               "supersample every pixel, not only geometry edges (slower, same look)");
  app.add_option("-j,--jobs", opt->jobs, "render threads (0 = all cores)")->capture_default_str()
      ->check(FiniteRange(0, 1024));
  app.add_option("--seed", opt->seed, "seed of the scene textures, handheld jitter and noise")
      ->capture_default_str()
      ->check(FiniteRange(0, 4294967295));
  app.add_option("--crf", opt->crf, "x264 CRF of the clean presets (lower = better)")
      ->capture_default_str()
      ->check(FiniteRange(0, 51));
  app.add_option("--noisy-crf", opt->noisy_crf, "x264 CRF of the noise_compression preset")
      ->capture_default_str()
      ->check(FiniteRange(0, 51));
  app.add_option("--x264-preset", opt->x264_preset, "x264 speed preset")->capture_default_str();
  app.add_option("--shutter", opt->shutter,
                 "exposure time / frame interval of motion-blurred presets (0.5 = 180 deg)")
      ->capture_default_str()
      ->check(FiniteRange(0, 1));
}

void PrintPresetList() {
  for (const std::string& name : SynthPresetNames())
    std::printf("%-20s %s\n", name.c_str(), SynthPresetDescription(name).c_str());
  std::printf("\nwith independently moving objects (--movers):\n");
  for (const std::string& name : SynthMoverPresetNames())
    std::printf("%-20s %s\n", name.c_str(), SynthPresetDescription(name).c_str());
}

// The presets to render, in the order asked, each once.
std::vector<std::string> PresetsToRender(const SynthArgs& a) {
  std::vector<std::string> todo;
  std::set<std::string> seen;
  auto add = [&](const std::vector<std::string>& names) {
    for (const std::string& n : names) {
      SynthPresetDescription(n);  // throws UsageError for unknown names
      if (seen.insert(n).second) todo.push_back(n);
    }
  };
  if (a.all) add(SynthPresetNames());
  if (a.table1) add(SynthTable1PresetNames());
  if (a.hard) add(SynthHardPresetNames());
  if (a.movers) add(SynthMoverPresetNames());
  add(a.presets);
  if (todo.empty())
    throw UsageError("no preset given (name presets, or --all/--table1/--hard/--movers)");
  return todo;
}

// Each clip's pair is committed together by SynthClip; the names are
// checked (a directory or a device in the way) before any rendering.
void CheckSynthOutputs(const std::string& out_dir, const std::vector<std::string>& todo) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  std::vector<NamedPath> outputs = {{out_dir, "-o", /*folder=*/true}};
  for (const std::string& name : todo) {
    const std::filesystem::path stem = std::filesystem::path(out_dir) / name;
    outputs.push_back({stem.string() + ".mp4", "-o"});
    outputs.push_back({stem.string() + ".camera.csv", "-o"});
  }
  CheckOutputPaths({}, outputs);
}

void RenderPresets(const std::vector<std::string>& todo, SynthOptions opt,
                   const std::string& out_dir) {
  std::unique_ptr<Progress> progress;  // one per clip
  opt.progress = [&](const std::string&, int done, int total) { progress->Update(done, total); };
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < todo.size(); ++i) {
    const std::string& name = todo[i];
    const std::string label =
        "synth [" + std::to_string(i + 1) + "/" + std::to_string(todo.size()) + "] " + name;
    progress = std::make_unique<Progress>(std::cerr, ProgressModeFor(false), label, "frames");
    const SynthResult r = SynthClip(name, opt, out_dir);
    progress->Close();
    std::printf("%s\n%s\n", r.video_path.c_str(), r.camera_path.c_str());
    std::fflush(stdout);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%zu clip(s) in %.1f s\n", todo.size(), s);
}

}  // namespace

int RunSynth(int argc, char** argv) {
  CLI::App app{
      "Render synthetic clips of a procedural hall with two characters, with exact ground-truth "
      "camera paths: <OUT_DIR>/<preset>.mp4 (H.264) and <OUT_DIR>/<preset>.camera.csv. "
      "Presets: the seven camera effects of the paper's Table 1 and hard cases (--list). "
      "Details: docs/synth.md.",
      argv[0]};
  SynthArgs a;
  SynthOptions opt;
  AddPresetOptions(app, &a, &opt);
  AddRenderOptions(app, &a, &opt);
  return RunApp(app, argc, argv, [&]() {
    if (a.list) {
      PrintPresetList();
      return kExitOk;
    }
    const std::vector<std::string> todo = PresetsToRender(a);
    opt.has_distortion = a.distortion->count() > 0;
    opt.distortion_k1 = a.distortion_k1;
    if (a.out_dir.empty()) throw UsageError("-o OUT_DIR is required");
    opt.adaptive = !a.full_ss;
    opt.Check();
    CheckSynthOutputs(a.out_dir, todo);
    RenderPresets(todo, opt, a.out_dir);
    return kExitOk;
  });
}

}  // namespace hapcine::cli
