// hapcine estimate: camera path (rotation, translation, zoom) from a video.
// A thin mapping of flags onto EstimatorOptions; the work is
// EstimateCameraPathFromFile() in estimate/camera_estimator.h, documented in
// docs/estimate.md.

#include <filesystem>
#include <iostream>
#include <set>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/diagnostics.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "estimate/camera_estimator.h"
#include "estimate/shot_quality.h"

namespace hapcine::cli {
namespace {

// The --report file (docs/formats.md "Estimate report").
void WriteReport(const JsonDiagnostics& diagnostics, const std::string& video, const CameraPath& path,
                 const std::string& report) {
  nlohmann::json header = {{"format", "hapcine-estimate-report"}, {"version", 1}, {"video", video},
                           {"frames", path.frames.size()}, {"stages", nlohmann::json::array()},
                           {"windows", nlohmann::json::array()}};
  for (const auto& [key, value] : path.metadata) header["metadata"][key] = value;
  header["shot_quality"] = nlohmann::json::array();
  for (const ShotQuality& q : ReadShotQuality(path)) header["shot_quality"].push_back(ShotQualityJson(q));
  AtomicFile out(report);
  out.stream() << diagnostics.Document(header).dump(1, ' ', false,
                                                   nlohmann::json::error_handler_t::replace)
               << "\n";
  out.Commit();
}

// Everything the command line sets besides EstimatorOptions.
struct EstimateArgs {
  std::string video, output, report;
  double fps = 0;
  bool fast = false, draft = false, quiet = false, report_detail = false;
  // Flags that switch off a default of EstimatorOptions.
  bool no_smooth = false, no_freedom_test = false, no_plane_prior = false, no_klt_predict = false;
  bool no_bridge_breaks = false;
};

// The preset goes in first, so options given beside --fast or --draft still
// win.
void ApplyPresets(int argc, char** argv, EstimatorOptions* opt) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--fast") ApplyFastPreset(opt);
    if (std::string(argv[i]) == "--draft") ApplyDraftPreset(opt);
  }
}

// The video, the output, the presets and what the frames are decoded into.
void AddInputOptions(CLI::App& app, EstimateArgs* a, EstimatorOptions* opt) {
  app.add_option("video", a->video, "input video (anything FFmpeg reads) or image folder/pattern")
      ->required();
  app.add_option("-o,--output", a->output, "output camera path (*.camera.csv), written atomically")
      ->required();
  app.add_option("--fps", a->fps,
                 "frame rate of an image folder or pattern (default 24), written in the header; "
                 "a video's times come from its timestamps")
      ->check(FiniteRange(0.001, 1000));
  app.add_flag("--fast", a->fast,
               "cheaper analysis (docs/estimate.md \"Speed\"): " + FastPresetSummary() +
                   "; options given beside it win");
  app.add_flag("--draft", a->draft,
               "~1.4x decoding time, least accurate (docs/estimate.md \"Accuracy\"): " +
                   DraftPresetSummary() + "; options given beside it win");
  app.add_flag("--skip-nonref", opt->frames.skip_nonref_frames,
               "decode only the frames others are predicted from (about half of H.264/HEVC "
               "with B-frames): faster; the skipped frames' poses are interpolated between "
               "their neighbours' at lower confidence; ~2.3x decoding time instead of ~3.2x "
               "(docs/estimate.md \"Accuracy\")");
  app.add_option("--backend", opt->backend,
                 "hapcine: tracks + model selection + bundle adjustment; colmap: COLMAP "
                 "incremental SfM (needs translation to initialise)")
      ->capture_default_str();
  app.add_option("--max-side", opt->frames.max_working_side,
                 "longest side of the working images, pixels (0 = decoded size)")
      ->capture_default_str()
      ->check(FiniteRange(0, 16384));
}

// How many tracks and points each window's bundle adjustment gets.
void AddWindowOptions(CLI::App& app, EstimatorOptions* opt) {
  app.add_option("--tracks", opt->tracker.max_tracks, "wanted live feature tracks per frame")
      ->capture_default_str()
      ->check(FiniteRange(10, 100000));
  app.add_option("--window", opt->estimator.window_frames,
                 "frames per bundle-adjustment window (long shots are solved in overlapping "
                 "windows, so memory is flat)")
      ->capture_default_str()
      ->check(FiniteRange(10, 10000));
  app.add_option("--points", opt->estimator.max_points,
                 "3-D points per window")
      ->capture_default_str()
      ->check(FiniteRange(20, 100000));
  app.add_option("--point-grid", opt->estimator.point_grid_cells,
                 "spread each window's points over N x N image cells, longest tracks first in "
                 "each cell (0: the longest tracks anywhere)")
      ->capture_default_str()
      ->check(FiniteRange(0, 100));
  app.add_option("--spread-points-factor", opt->estimator.spread_points_factor,
                 "translating windows (those the point grid spreads) take --points x this many "
                 "points, since the whole-track cut drops about half of them near silhouettes")
      ->capture_default_str()
      ->check(FiniteRange(1, 10));
  app.add_option("--track-rms-cut", opt->estimator.track_rms_cut_px,
                 "drop a window's track whole when its reprojection RMS exceeds this (pixels at "
                 "960 px width; occlusion-edge tracks)")
      ->capture_default_str()
      ->check(FiniteRange(0.01, 1000));
}

// The choice of motion model, the lens and the focal-length prior.
void AddModelOptions(CLI::App& app, EstimateArgs* a, EstimatorOptions* opt) {
  app.add_flag("--no-freedom-test", a->no_freedom_test,
               "keep the two-view labels: no window-level BIC test of a few translating (or "
               "zooming) intervals, nor of zoom intervals among translating ones "
               "(docs/estimate.md, step 4)");
  app.add_flag(
         "--lens-distortion,!--no-lens-distortion", opt->lens_distortion,
         "estimate one radial distortion coefficient k1 from frame pairs of the first shot's "
         "first 6 s and, where it pays for itself, estimate again with the tracks undistorted "
         "(header k1=; on unless --lens-bundle or --lens-k1 gives the lens; docs/estimate.md "
         "\"Lens distortion\")")
      ->capture_default_str();
  app.add_flag("--lens-bundle,!--no-lens-bundle", opt->lens_bundle,
               "measure k1 in a bundle adjustment of each of the first shot's first windows "
               "(--lens-windows; rigid points over many views); where two windows pay for their own "
               "k1 and all agree the estimation starts again with the tracks undistorted by the "
               "pooled k1 (header k1=; docs/estimate.md \"Lens distortion\")");
  app.add_option("--lens-windows", opt->lens_bundle_windows,
                 "--lens-bundle measures k1 in each of the first shot's first N windows and keeps it "
                 "only where they agree (same sign, within their standard errors); 1: the first "
                 "window alone")
      ->capture_default_str()
      ->check(FiniteRange(1, 8));
  app.add_option("--lens-k1", opt->lens_k1,
                 "a known radial distortion coefficient (ffmpeg lenscorrection's k1: r in "
                 "half-diagonals, barrel > 0): every track is undistorted with it, none is estimated")
      ->check(FiniteRange(-0.5, 0.5));
  app.add_flag("--no-plane-prior", a->no_plane_prior,
               "a dolly with a zoom along the optical axis keeps the depths its fit started from "
               "(the farthest points at infinity) instead of those that make a floor or wall "
               "parallel to the move, and the floor does not help choose between a forward and a "
               "backward move (docs/estimate.md, step 4)");
  app.add_flag("--drift-weights", opt->estimator.drift_weights,
               "weight each observation by the KLT drift expected at its track's age (frames since "
               "the point's first observation in the window), where a window's residuals grow with "
               "it; off by default: measured not to help (docs/estimate.md, \"Track drift weights\")");
  app.add_option("--blur-noise", opt->estimator.blur_noise_per_speed,
                 "those window-level tests count tracking noise growing with the image speed "
                 "(motion blur): px of noise per px/frame of motion, added in quadrature "
                 "(0: off; docs/estimate.md, step 4)")
      ->capture_default_str()
      ->check(FiniteRange(0, 1));
  app.add_option("--prior-fov", opt->estimator.prior_hfov_deg,
                 "horizontal field of view, degrees, assumed where the focal length cannot be "
                 "observed (no rotation)")
      ->capture_default_str()
      ->check(FiniteRange(1, 179));
  app.add_option("--keyframe-gap", opt->estimator.keyframe_max_gap,
                 "at least one keyframe every this many frames")
      ->capture_default_str()
      ->check(FiniteRange(1, 10000));
}

// Smoothing of the path, solver threads and the decoder's shortcuts.
void AddSmoothingAndThreadOptions(CLI::App& app, EstimateArgs* a, EstimatorOptions* opt) {
  app.add_flag("--no-smooth", a->no_smooth, "skip the zero-phase smoothing of the path");
  app.add_option("--smooth-sigma", opt->estimator.smooth_sigma_frames,
                 "Gaussian sigma of the zero-phase smoothing, frames")
      ->capture_default_str()
      ->check(FiniteRange(0, 1000));
  app.add_option("--threads", opt->estimator.num_threads, "Ceres solver threads")
      ->capture_default_str()
      ->check(FiniteRange(1, 256));
  app.add_flag("--skip-loop-filter", opt->frames.skip_loop_filter,
               "skip H.264/HEVC deblocking when decoding: ~10 % cheaper decoding, slightly "
               "blockier analysis images");
  app.add_option("--decode-threads", opt->frames.decode_threads,
                 "FFmpeg decoder threads (0 = FFmpeg's choice); decoding runs beside tracking")
      ->capture_default_str()
      ->check(FiniteRange(0, 256));
}

// The KLT tracker, stills linking and the solver's iterations.
void AddTrackerOptions(CLI::App& app, EstimateArgs* a, EstimatorOptions* opt) {
  app.add_option("--klt-window", opt->tracker.klt_window, "KLT window side, working pixels (odd)")
      ->capture_default_str()
      ->check(FiniteRange(5, 101));
  app.add_option("--klt-anchor-frames", opt->tracker.klt_anchor_frames,
                 "bound KLT drift: track each point from the frame where it was detected too, moving "
                 "that anchor on every N frames; a track whose correction is an outlier ends (0 = off)")
      ->capture_default_str()
      ->check(FiniteRange(0, 10000));
  app.add_option("--klt-anchor-min", opt->tracker.klt_anchor_min_px,
                 "with --klt-anchor-frames: the smallest anchor correction that can end a track, working pixels")
      ->capture_default_str()
      ->check(FiniteRange(0.01, 100));
  app.add_flag("--klt-anchor-affine", opt->tracker.klt_anchor_affine,
               "with --klt-anchor-frames: align each anchor's patch by an affine warp (follows its change of "
               "shape as the view turns); a track whose patch no longer aligns, or aligns worse than the "
               "frame's others (robust outlier), ends");
  app.add_flag("--revisit-links", opt->tracker.revisit_links,
               "link the views of a shot that KLT no longer connects but that look alike (an orbit "
               "coming round) by descriptors, continuing the earlier view's tracks "
               "(docs/extract.md \"Revisit links\")");
  app.add_flag(
      "--loop-bundle", opt->estimator.loop_bundle,
      "after a translating shot's windows, adjust all its keyframes together where tracks close a "
      "loop no window saw whole (with --revisit-links; docs/estimate.md \"Loop bundle\")");
  app.add_flag("--no-klt-predict", a->no_klt_predict,
               "start each KLT search at zero motion; by default a track moving more than a "
               "KLT window per frame starts where its last motion takes it (whip pans)");
  app.add_flag("--no-bridge-breaks", a->no_bridge_breaks,
               "split a shot wherever tracking breaks without a cut; by default the frames after a "
               "break are linked by descriptors to the frame before it for up to half a second, and "
               "the first that links continues the shot (docs/extract.md \"Breaks inside a take\")");
  app.add_flag("--flat-field", opt->tracker.flat_field_vignetting,
               "estimate the lens's vignetting from the tracks' brightness as they cross the picture and, "
               "once it shows the picture darkening towards its corners (5 % or more), track frames "
               "divided by that field: LK reads the edges' motion short under a fall-off "
               "(docs/extract.md \"Vignetting\")");
  app.add_flag("--match-fade-contrast", opt->tracker.match_fade_contrast,
               "in a fade (a frame's mean and contrast changed by one factor of more than 2 %), "
               "track it at the last frame's mean and contrast: LK assumes constant brightness "
               "(docs/extract.md \"inside a fade\")");
  app.add_flag("--stills", opt->tracker.stills,
               "every frame is a still: link frames by descriptors (SIFT; KLT only where they are as "
               "close as a video's), split shots only where nothing links, do not smooth the path "
               "(automatic for image folders and patterns, and for a video whose shot jumps beyond KLT's "
               "reach from its first step)");
  app.add_option("--pyramid-levels", opt->tracker.pyramid_levels, "KLT pyramid levels")
      ->check(FiniteRange(1, 8));
  app.add_option("--klt-coarse-iterations", opt->tracker.klt_coarse_iterations,
                 "KLT iterations on the coarser pyramid levels")
      ->check(FiniteRange(1, 100));
  app.add_option("--klt-coarse-step", opt->tracker.klt_coarse_step_px,
                 "KLT stop step on the coarser pyramid levels, pixels of that level")
      ->check(FiniteRange(0, 1));
  app.add_option("--ba-iterations", opt->estimator.ba_iterations, "Ceres iterations per window")
      ->check(FiniteRange(1, 10000));
  app.add_option("--focal-min-turn", opt->estimator.min_rotation_for_focal_deg,
                 "optical-axis turn (degrees) a window needs to self-calibrate the focal; above any turn "
                 "the focal stays at --prior-fov")
      ->check(FiniteRange(0, 360))
      ->capture_default_str();
  app.add_option("--colmap-binary", opt->colmap_binary, "COLMAP executable (--backend colmap)")
      ->capture_default_str();
}

void AddOutputOptions(CLI::App& app, EstimateArgs* a) {
  app.add_flag("-q,--quiet", a->quiet, "no progress output");
  app.add_option("--report", a->report,
                 "also write a JSON report (docs/formats.md \"Estimate report\"): per window the "
                 "candidate solves and their scores, the model taken, inliers, the bundle adjustment's "
                 "summary and timings; per run the stage timings; written atomically");
  app.add_flag("--report-detail", a->report_detail,
               "the report also lists every window track's RMS, every frame's shot-cut cues and each window's "
               "focal profile (slower: one solve per profile shift)");
}

// What most users need stays on top of --help; the algorithm's knobs
// (docs/estimate.md, "Options") are listed after them.
void GroupTuningOptions(CLI::App& app) {
  for (const char* name :
       {"--tracks", "--window", "--points", "--point-grid", "--spread-points-factor", "--track-rms-cut",
        "--no-freedom-test", "--no-plane-prior", "--drift-weights", "--blur-noise", "--keyframe-gap",
        "--no-smooth", "--smooth-sigma", "--klt-window", "--klt-anchor-frames", "--klt-anchor-min",
        "--klt-anchor-affine", "--revisit-links", "--loop-bundle", "--no-klt-predict", "--no-bridge-breaks",
        "--flat-field",
        "--match-fade-contrast", "--stills", "--skip-loop-filter", "--decode-threads",
        "--pyramid-levels", "--klt-coarse-iterations", "--klt-coarse-step", "--ba-iterations",
        "--focal-min-turn"})
    app.get_option(name)->group("Tuning");
}

// The switched-off defaults and --fps into `opt`, then its checks.
void CompleteOptions(const EstimateArgs& a, EstimatorOptions* opt) {
  opt->estimator.smooth = !a.no_smooth;
  if (a.no_freedom_test) opt->estimator.freedom_test = false;
  if (a.no_plane_prior) opt->estimator.motion_plane_prior = false;
  if (a.no_klt_predict) opt->tracker.klt_predict = false;
  if (a.no_bridge_breaks) opt->tracker.bridge_breaks = false;
  if (a.fps > 0) {
    std::error_code ec;
    if (a.video.find('%') == std::string::npos && !std::filesystem::is_directory(a.video, ec))
      throw UsageError("--fps is for image folders and patterns; a video's times come from its timestamps");
    opt->frames.image_sequence_fps = a.fps;
  }
  opt->Check();
}

// The path's warning and one line per doubtful shot (the rule:
// estimate/shot_quality.h), even with --quiet.
void PrintWarnings(const std::string& video, const CameraPath& path) {
  if (const auto w = path.metadata.find("warning"); w != path.metadata.end())
    std::cerr << "hapcine estimate: " << video << ": warning: " << w->second << "\n";
  // One line per doubtful shot and per shot with an undecided zoom (the
  // rules: estimate/shot_quality.h), even with --quiet.
  for (const ShotQuality& q : ReadShotQuality(path)) {
    if (q.doubtful) std::cerr << "hapcine estimate: " << video << ": " << DoubtfulShotLine(q) << "\n";
    if (q.still_border)
      std::cerr << "hapcine estimate: " << video << ": " << StillBorderLine(q) << "\n";
    if (q.zoom_ambiguous.value_or(0) > 0)
      std::cerr << "hapcine estimate: " << video << ": warning: " << AmbiguousZoomLine(q) << "\n";
  }
}

// Estimates the path and writes it (and the report) atomically.
int Estimate(const EstimateArgs& a, EstimatorOptions opt) {
  OutputSet outputs({{a.video, "VIDEO"}}, {{a.output, "-o"}, {a.report, "--report"}});
  std::set<std::string> kinds{"stage", "window", "lens_distortion", "vignetting", "loop_bundle"};
  if (a.report_detail) kinds.insert({"track_rms", "cut_cues", "descriptor_links", "focal_profile", "focal_pull",
                                    "track_drift"});
  JsonDiagnostics diagnostics(kinds);
  if (!a.report.empty()) opt.diagnostics = &diagnostics;
  Progress progress(std::cerr, ProgressModeFor(a.quiet), "estimate", "frames");
  const CameraPath path = EstimateCameraPathFromFile(
      a.video, opt, [&](long done, long total) { progress.Update(done, total); });
  if (path.frames.size() < 2)
    throw Error(a.video, std::to_string(path.frames.size()) +
                             " video frame(s): camera motion needs at least two");
  PrintWarnings(a.video, path);
  WriteCameraPathFile(path, a.output);
  if (!a.report.empty()) WriteReport(diagnostics, a.video, path, a.report);
  outputs.CommitAll();
  progress.Finish(static_cast<double>(path.frames.size()));
  return kExitOk;
}

}  // namespace

int RunEstimate(int argc, char** argv) {
  CLI::App app{
      "Estimate the camera path (rotation, translation, zoom) of a video and write it as a "
      "*.camera.csv file (docs/estimate.md; the format: docs/formats.md). Per shot and segment the simplest "
      "motion model is chosen (static, zoom, rotation, rotation+zoom, general, general+zoom).",
      argv[0]};
  EstimateArgs a;
  EstimatorOptions opt;
  ApplyPresets(argc, argv, &opt);
  AddInputOptions(app, &a, &opt);
  AddWindowOptions(app, &opt);
  AddModelOptions(app, &a, &opt);
  AddSmoothingAndThreadOptions(app, &a, &opt);
  AddTrackerOptions(app, &a, &opt);
  AddOutputOptions(app, &a);
  GroupTuningOptions(app);
  return RunApp(app, argc, argv, [&]() {
    // The pairs' measurement is the default and gives way to another source
    // of k1; asked for beside one, it is a contradiction.
    if (app.get_option("--lens-distortion")->count() > 0 && opt.lens_distortion &&
        (opt.lens_bundle || opt.lens_k1 != 0))
      throw UsageError(
          "--lens-distortion, --lens-bundle and --lens-k1 exclude each other: choose one");
    CompleteOptions(a, &opt);
    return Estimate(a, opt);
  });
}

}  // namespace hapcine::cli
