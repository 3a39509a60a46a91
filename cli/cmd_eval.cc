// hapcine eval: compare an estimated camera path against ground truth.
// A thin mapping of flags onto EvalOptions; the metrics live in datasets/eval.h
// and are defined in docs/eval.md.

#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/output_files.h"
#include "datasets/eval.h"
#include "datasets/eval_haptics.h"
#include "core/haptic_track.h"
#include "haptics/camera_signals.h"
#include "haptics/false_cues.h"
#include "haptics/hjif_import.h"

namespace hapcine::cli {

namespace {

// `eval --haptic`: the haptic difference of the two paths' tracks, or of the
// estimate's track and `track_file` (*.haptic.csv or .hjif) when given.
HapticEvalReport HapticReport(const CameraPath& gt, const CameraPath& est,
                              const EvalReport& report, const std::string& model, double rate_hz,
                              const std::string& track_file) {
  HapticOptions ho;
  ho.model = HapticModelFromName(model);
  ho.rate_hz = rate_hz;
  ho.source = report.gt_source;
  ho.Check();
  // The haptic checks (gaps, absurd positions) with file line numbers.
  for (const auto& [path, file] : {std::pair<const CameraPath*, std::string>{&gt, report.gt_source},
                                   {&est, report.est_source}}) {
    const std::vector<int> lines = CsvDataRowLines(file);
    ValidatePathForHaptics(*path, file, ho.max_gap_s, &lines);
  }
  const HapticTrack reference = track_file.empty() ? HapticTrack() : ReadAnyHapticTrackFile(track_file);
  return EvaluateHapticDifferenceToTrack(reference, gt, est, report, ho);
}

// The false cues of --track, or of the default cinematic track of `path`.
std::vector<ShotFalseCue> FalseCuesOf(const CameraPath& path, const std::string& path_file,
                                      const std::string& track_file, double rate_hz) {
  HapticOptions ho;
  ho.rate_hz = rate_hz;
  ho.source = path_file;
  ho.Check();
  const std::vector<int> lines = CsvDataRowLines(path_file);
  ValidatePathForHaptics(path, path_file, ho.max_gap_s, &lines);
  const HapticTrack track =
      track_file.empty() ? MakeHapticTrack(path, ho) : ReadAnyHapticTrackFile(track_file);
  return MeasureFalseCues(path, track, ho.seat, ho.cinematic);
}

void AddFalseCueOptions(CLI::App& app, bool* false_cues, std::string* track_file) {
  app.add_flag("--false-cues", *false_cues,
               "per shot of --gt, the largest counter-motion of a haptic track (mm) and its\n"
               "duration: how far an actuator moves back while the camera keeps moving the\n"
               "same way (docs/haptics.md). The track: --track, else the default cinematic track\n"
               "of --gt");
  app.add_option("--track", *track_file, "haptic track measured by --false-cues (*.haptic.csv)");
}

std::string JsonText(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void WriteJsonFile(const nlohmann::json& j, const std::string& path) {
  if (path.empty()) return;
  AtomicFile out(path);
  out.stream() << JsonText(j);
  out.Commit();
}

// `eval --false-cues` without --est: the false cues of one track.
int RunFalseCues(const std::string& gt_file, const std::string& track_file, bool json,
                 const std::string& json_out, double rate_hz) {
  OutputSet outputs({{gt_file, "--gt"}, {track_file, "--track"}}, {{json_out, "-o"}});
  const CameraPath path = ReadCameraPathFile(gt_file);
  const std::vector<ShotFalseCue> cues = FalseCuesOf(path, gt_file, track_file, rate_hz);
  nlohmann::json j = {{"gt", gt_file}, {"track", track_file.empty() ? "default" : track_file},
                      {"false_cues", FalseCuesToJson(cues)}};
  WriteJsonFile(j, json_out);
  outputs.CommitAll();
  std::cout << (json ? JsonText(j) : FormatFalseCueTable(cues));
  return kExitOk;
}

// Everything the command line sets besides EvalOptions.
struct EvalArgs {
  std::string gt_file, est_file, json_out, per_frame_out;
  std::string align = "sim3", matching = "auto";
  bool json = false, no_per_shot = false;
  bool haptic = false;
  std::string haptic_model = "cinematic";
  std::string haptic_track;
  double haptic_rate = 1000;
  CLI::Option* haptic_model_option = nullptr;
  bool false_cues = false;
  std::string track_file;
};

void AddPathOptions(CLI::App& app, EvalArgs* a, EvalOptions* opt) {
  app.add_option("--gt", a->gt_file, "ground-truth camera path (*.camera.csv)")->required();
  app.add_option("--est", a->est_file,
                 "estimated camera path (*.camera.csv); not needed with --false-cues alone");
  app.add_flag("--json", a->json, "print the report as JSON instead of a table");
  app.add_option("-o,--output", a->json_out, "also write the JSON report to this file (atomic)");
  app.add_option("--align", a->align,
                 "alignment of the camera centres before ATE/RPE: sim3 (Umeyama with scale, "
                 "like evo -as; for monocular estimates), se3 (rigid, evo -a), none")
      ->capture_default_str()->check(CLI::IsMember({"sim3", "se3", "none"}));
  app.add_option("--rpe-delta", opt->rpe_delta, "RPE frame distance (evo --delta N --delta_unit f)")
      ->capture_default_str()
      ->check(FiniteRange(1, 1e6));
  app.add_option("--match", a->matching,
                 "frame matching: frame (same frame index), time (nearest time_s within half a "
                 "frame), auto (frame index; time when under half the frames share an index)")
      ->capture_default_str()->check(CLI::IsMember({"auto", "frame", "time"}));
  app.add_flag("--no-per-shot", a->no_per_shot,
               "ignore the `shot` column: evaluate the whole clip aligned on its first frame");
  app.add_option("--static-length", opt->static_path_length,
                 "GT path length below which the GT camera counts as not moving (ATE % n/a, "
                 "estimated path length reported as spurious translation), GT units")
      ->capture_default_str()
      ->check(FiniteRange(0, 1e6));
  app.add_option("--shot-tolerance", opt->shot_tolerance_frames,
                 "an estimated shot boundary within this many frames of a ground-truth one is "
                 "found (shot boundaries: precision/recall)")
      ->capture_default_str()
      ->check(FiniteRange(0, 1e6));
  app.add_option("--per-frame", a->per_frame_out, "write per-frame errors as CSV (atomic)");
}

void AddHapticOptions(CLI::App& app, EvalArgs* a) {
  app.add_flag("--haptic", a->haptic,
               "also compare the haptic tracks of the two paths (the estimate scaled to GT units\n"
               "per shot; the cinematic scaling computed from the GT and used for both)");
  a->haptic_model_option =
      app.add_option("--haptic-model", a->haptic_model,
                     "model of the compared tracks (implies --haptic)")
          ->capture_default_str()
          ->check(CLI::IsMember({"cinematic", "semantic", "random", "none"}));
  app.add_option("--haptic-track", a->haptic_track,
                 "compare the estimate's haptic track with this track (*.haptic.csv, or an\n"
                 "MPEG-I Haptics .hjif with Position perceptions) instead of the GT path's "
                 "(implies --haptic)");
  app.add_option("--haptic-rate", a->haptic_rate, "rate of the compared tracks, Hz")
      ->capture_default_str()
      ->check(FiniteRange(10, 10000));
  AddFalseCueOptions(app, &a->false_cues, &a->track_file);
}

// `eval --gt G --est E`: the report, with the haptic difference and false
// cues when asked.
int RunCompare(const EvalArgs& a, EvalOptions opt) {
  opt.align = ParseTrajectoryAlignment(a.align);
  opt.matching = ParseFrameMatching(a.matching);
  opt.per_shot = !a.no_per_shot;
  opt.Check();
  OutputSet outputs({{a.gt_file, "--gt"}, {a.est_file, "--est"},
                     {a.haptic_track, "--haptic-track"}, {a.track_file, "--track"}},
                    {{a.json_out, "-o"}, {a.per_frame_out, "--per-frame"}});
  const CameraPath gt = ReadCameraPathFile(a.gt_file);
  const CameraPath est = ReadCameraPathFile(a.est_file);
  EvalReport report = EvaluateCameraPaths(gt, est, opt);
  report.gt_source = a.gt_file;
  report.est_source = a.est_file;
  nlohmann::json j = EvalReportToJson(report);
  std::optional<HapticEvalReport> haptic_report;
  if (a.haptic || a.haptic_model_option->count() > 0 || !a.haptic_track.empty()) {
    haptic_report = HapticReport(gt, est, report, a.haptic_model, a.haptic_rate, a.haptic_track);
    j["haptic"] = HapticEvalToJson(*haptic_report);
  }
  std::vector<ShotFalseCue> cues;
  if (a.false_cues) {
    cues = FalseCuesOf(gt, a.gt_file, a.track_file, a.haptic_rate);
    j["false_cues"] = FalseCuesToJson(cues);
  }
  WriteJsonFile(j, a.json_out);
  if (!a.per_frame_out.empty()) WritePerFrameErrorsFile(report, a.per_frame_out);
  outputs.CommitAll();
  if (a.json) {
    std::cout << JsonText(j);
    return kExitOk;
  }
  std::cout << FormatEvalTable(report);
  if (haptic_report) std::cout << "\n" << FormatHapticEvalTable(*haptic_report);
  if (a.false_cues) std::cout << "\n" << FormatFalseCueTable(cues);
  return kExitOk;
}

}  // namespace

int RunEval(int argc, char** argv) {
  CLI::App app{
      "Compare an estimated camera path (*.camera.csv) against ground truth: rotation error, "
      "FOV and zoom-ratio error, ATE after Umeyama alignment, RPE, per shot when a `shot` column "
      "exists. With --haptic, also the difference between the haptic tracks the two paths give\n"
      "(same model, same scaling: docs/haptics.md). Metric definitions: docs/eval.md.",
      argv[0]};
  EvalArgs a;
  EvalOptions opt;
  AddPathOptions(app, &a, &opt);
  AddHapticOptions(app, &a);
  return RunApp(app, argc, argv, [&]() {
    if (!a.track_file.empty() && !a.false_cues) throw UsageError("--track needs --false-cues");
    if (a.false_cues && a.est_file.empty())
      return RunFalseCues(a.gt_file, a.track_file, a.json, a.json_out, a.haptic_rate);
    if (a.est_file.empty()) throw UsageError("--est is required (or --false-cues alone)");
    return RunCompare(a, opt);
  });
}

}  // namespace hapcine::cli
