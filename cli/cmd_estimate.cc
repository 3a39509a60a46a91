// hapcine estimate: camera path (rotation, translation, zoom) from a video.
// A thin mapping of flags onto EstimatorOptions; the work is
// EstimateCameraPathFromFile() in estimate/camera_estimator.h, documented in
// docs/estimate.md.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli/command.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "estimate/camera_estimator.h"

namespace hapcine::cli {
namespace {

// Frames done / total, rate and ETA: a bar on a terminal, a line every ~5 s otherwise.
class EstimateProgress {
 public:
  explicit EstimateProgress(bool quiet)
      : quiet_(quiet), tty_(::isatty(STDERR_FILENO) != 0), start_(Clock::now()), last_(start_) {}

  void Update(long done, long total) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (since < (tty_ ? 0.2 : 5.0)) return;
    last_ = now;
    const double fps = elapsed > 0 ? done / elapsed : 0;
    if (tty_) {
      if (total > 0) {
        const int width = 30;
        const int filled = static_cast<int>(std::min<long>(done, total) * width / total);
        const double eta = fps > 0 ? (total - std::min(done, total)) / fps : 0;
        std::fprintf(stderr, "\r[%s%s] %ld/%ld frames  %.1f fps  ETA %.0f s   ",
                     std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                     done, total, fps, eta);
      } else {
        std::fprintf(stderr, "\r%ld frames  %.1f fps   ", done, fps);
      }
    } else {
      std::fprintf(stderr, "estimate: %ld/%ld frames, %.1f fps\n", done, total, fps);
    }
    std::fflush(stderr);
    drawn_ = true;
  }
  void Done(long frames) {
    if (quiet_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (tty_ && drawn_) std::fprintf(stderr, "\n");
    std::fprintf(stderr, "estimate: %ld frames in %.1f s (%.1f fps)\n", frames, elapsed,
                 elapsed > 0 ? frames / elapsed : 0.0);
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_, tty_, drawn_ = false;
  Clock::time_point start_, last_;
};

}  // namespace

int RunEstimate(int argc, char** argv) {
  CLI::App app{
      "Estimate the camera path (rotation, translation, zoom) of a video and write it as a "
      "*.camera.csv file (docs/estimate.md; the format: docs/formats.md). Per shot and segment the simplest "
      "motion model is chosen (static, zoom, rotation, rotation+zoom, general, general+zoom).",
      argv[0]};
  std::string video, output;
  EstimatorOptions opt;
  bool no_smooth = false, quiet = false, fast = false, draft = false;
  // The preset goes in first, so options given beside --fast or --draft
  // still win.
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--fast") ApplyFastPreset(&opt);
    if (std::string(argv[i]) == "--draft") ApplyDraftPreset(&opt);
  }
  app.add_option("video", video, "input video (anything FFmpeg reads) or image folder/pattern")
      ->required();
  app.add_option("-o,--output", output, "output camera path (*.camera.csv), written atomically")
      ->required();
  app.add_flag("--fast", fast,
               "cheaper analysis (docs/estimate.md \"Speed\"): " + FastPresetSummary() +
                   "; options given beside it win");
  app.add_flag("--draft", draft,
               "~1.4x decoding time, least accurate (docs/estimate.md \"Accuracy\"): " +
                   DraftPresetSummary() + "; options given beside it win");
  app.add_flag("--skip-nonref", opt.frames.skip_nonref_frames,
               "decode only the frames others are predicted from (about half of H.264/HEVC "
               "with B-frames): faster; the skipped frames' poses are interpolated between "
               "their neighbours' at lower confidence; ~2.3x decoding time instead of ~3.2x "
               "(docs/estimate.md \"Accuracy\")");
  app.add_option("--backend", opt.backend,
                 "hapcine: tracks + model selection + bundle adjustment; colmap: COLMAP "
                 "incremental SfM (needs translation to initialise)")
      ->capture_default_str();
  app.add_option("--max-side", opt.frames.max_working_side,
                 "longest side of the working images, pixels (0 = decoded size)")
      ->capture_default_str();
  app.add_option("--tracks", opt.tracker.max_tracks, "wanted live feature tracks per frame")
      ->capture_default_str();
  app.add_option("--window", opt.estimator.window_frames,
                 "frames per bundle-adjustment window (long shots are solved in overlapping "
                 "windows, so memory is flat)")
      ->capture_default_str();
  app.add_option("--points", opt.estimator.max_points,
                 "3-D points per window")
      ->capture_default_str();
  app.add_option("--point-grid", opt.estimator.point_grid_cells,
                 "spread each window's points over N x N image cells, longest tracks first in "
                 "each cell (0: the longest tracks anywhere)")
      ->capture_default_str();
  app.add_option("--spread-points-factor", opt.estimator.spread_points_factor,
                 "translating windows (those the point grid spreads) take --points x this many "
                 "points, since the whole-track cut drops about half of them near silhouettes")
      ->capture_default_str();
  app.add_option("--track-rms-cut", opt.estimator.track_rms_cut_px,
                 "drop a window's track whole when its reprojection RMS exceeds this (pixels at "
                 "960 px width; occlusion-edge tracks)")
      ->capture_default_str();
  bool no_freedom_test = false;
  app.add_flag("--no-freedom-test", no_freedom_test,
               "keep the two-view labels: no window-level BIC test of a few translating (or "
               "zooming) intervals, nor of zoom intervals among translating ones "
               "(docs/estimate.md, step 4)");
  bool no_plane_prior = false;
  app.add_flag("--no-plane-prior", no_plane_prior,
               "a dolly with a zoom along the optical axis keeps the depths its fit started from "
               "(the farthest points at infinity) instead of those that make a floor or wall "
               "parallel to the move, and the floor does not help choose between a forward and a "
               "backward move (docs/estimate.md, step 4)");
  app.add_option("--blur-noise", opt.estimator.blur_noise_per_speed,
                 "those window-level tests count tracking noise growing with the image speed "
                 "(motion blur): px of noise per px/frame of motion, added in quadrature "
                 "(0: off; docs/estimate.md, step 4)")
      ->capture_default_str();
  app.add_option("--prior-fov", opt.estimator.prior_hfov_deg,
                 "horizontal field of view, degrees, assumed where the focal length cannot be "
                 "observed (no rotation)")
      ->capture_default_str();
  app.add_option("--keyframe-gap", opt.estimator.keyframe_max_gap,
                 "at least one keyframe every this many frames")
      ->capture_default_str();
  app.add_flag("--no-smooth", no_smooth, "skip the zero-phase smoothing of the path");
  app.add_option("--smooth-sigma", opt.estimator.smooth_sigma_frames,
                 "Gaussian sigma of the zero-phase smoothing, frames")
      ->capture_default_str();
  app.add_option("--threads", opt.estimator.num_threads, "Ceres solver threads")
      ->capture_default_str();
  app.add_flag("--skip-loop-filter", opt.frames.skip_loop_filter,
               "skip H.264/HEVC deblocking when decoding: ~10 % cheaper decoding, slightly "
               "blockier analysis images");
  app.add_option("--decode-threads", opt.frames.decode_threads,
                 "FFmpeg decoder threads (0 = FFmpeg's choice); decoding runs beside tracking")
      ->capture_default_str();
  app.add_option("--klt-window", opt.tracker.klt_window, "KLT window side, working pixels (odd)")
      ->capture_default_str();
  bool no_klt_predict = false;
  app.add_flag("--no-klt-predict", no_klt_predict,
               "start each KLT search at zero motion; by default a track moving more than a "
               "KLT window per frame starts where its last motion takes it (whip pans)");
  // Tuning knobs for bench/speed.sh, not worth a line in --help.
  app.add_option("--pyramid-levels", opt.tracker.pyramid_levels, "KLT pyramid levels")
      ->group("");
  app.add_option("--klt-coarse-iterations", opt.tracker.klt_coarse_iterations,
                 "KLT iterations on the coarser pyramid levels")
      ->group("");
  app.add_option("--klt-coarse-step", opt.tracker.klt_coarse_step_px,
                 "KLT stop step on the coarser pyramid levels, pixels of that level")
      ->group("");
  app.add_option("--ba-iterations", opt.estimator.ba_iterations, "Ceres iterations per window")
      ->group("");
  app.add_option("--colmap-binary", opt.colmap_binary, "COLMAP executable (--backend colmap)")
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no progress output");
  // What most users need stays on top of --help; the algorithm's knobs
  // (docs/estimate.md, "Options") are listed after them.
  for (const char* name : {"--tracks", "--window", "--points", "--point-grid", "--spread-points-factor",
                           "--track-rms-cut", "--no-freedom-test", "--no-plane-prior", "--blur-noise",
                           "--keyframe-gap", "--no-smooth", "--smooth-sigma", "--klt-window",
                           "--no-klt-predict", "--skip-loop-filter", "--decode-threads"})
    app.get_option(name)->group("Tuning");

  return RunApp(app, argc, argv, [&]() {
    opt.estimator.smooth = !no_smooth;
    if (no_freedom_test) opt.estimator.freedom_test = false;
    if (no_plane_prior) opt.estimator.motion_plane_prior = false;
    if (no_klt_predict) opt.tracker.klt_predict = false;
    opt.Check();
    const std::filesystem::path out_path(output);
    const auto parent = out_path.has_parent_path() ? out_path.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(parent))
      throw Error(output, "output folder does not exist");
    EstimateProgress progress(quiet);
    const CameraPath path = EstimateCameraPathFromFile(
        video, opt, [&](long done, long total) { progress.Update(done, total); });
    if (path.frames.size() < 2)
      throw Error(video, std::to_string(path.frames.size()) +
                             " video frame(s): camera motion needs at least two");
    WriteCameraPathFile(path, output);
    progress.Done(static_cast<long>(path.frames.size()));
    return kExitOk;
  });
}

}  // namespace hapcine::cli
