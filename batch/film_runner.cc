#include "batch/film_runner.h"


#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "batch/content_hash.h"
#include "batch/json_bytes.h"
#include "batch/library.h"
#include "batch/state_files.h"
#include "batch/subprocess.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/shot_quality_header.h"

namespace hapcine::batch {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string HostName() {
  char buf[256] = {0};
  ::gethostname(buf, sizeof(buf) - 1);
  return buf;
}

// A step: its command and the output file names it must produce.
struct Step {
  std::string name;
  std::string key;                   // settings key of the step (stamp)
  std::vector<std::string> outputs;  // file names inside the output folder
  std::vector<std::string> command;  // writes those names inside .tmp/
};

// The key of a step that reads a haptic track: the haptics settings plus,
// when the film has an edits file, its content.
std::string TrackStepKey(const BatchOptions& options, const std::string& model,
                         const FilmLayout& layout) {
  const std::string key = HapticsStepKey(options, model);
  return layout.edits_hash.empty() ? key : Fnv1a64Hex(key + "\nedits:" + layout.edits_hash);
}

// The optional steps after haptics: a preview of the first model's track and
// the plots. Each reads the FINAL files of the steps before it.
void AddReviewSteps(const BatchOptions& options, const std::string& exe, const FilmPlan& film,
                    const FilmLayout& layout, std::vector<Step>* steps) {
  if (layout.models.empty()) return;
  const fs::path out(layout.output_dir), tmp = fs::path(layout.state_dir) / kTempDir;
  const ModelOutputs& first = layout.models.front();
  const std::string key = TrackStepKey(options, first.model, layout);
  if (!layout.preview.empty()) {
    steps->push_back({"preview", key, {layout.preview},
                      {exe, "preview", film.path, "--track", (out / first.haptic).string(),
                       "--camera", (out / layout.camera).string(), "-o",
                       (tmp / layout.preview).string()}});
  }
  // plot writes PREFIX.png: the prefix is the name without ".png".
  auto prefix = [&](const std::string& png) {
    return (tmp / png.substr(0, png.size() - 4)).string();
  };
  if (!layout.camera_plot.empty()) {
    steps->push_back({"plot-camera", EstimateStepKey(options), {layout.camera_plot},
                      {exe, "plot", "camera", (out / layout.camera).string(), "--format", "png",
                       "-o", prefix(layout.camera_plot)}});
  }
  if (!layout.haptic_plot.empty()) {
    steps->push_back({"plot-haptic", key, {layout.haptic_plot},
                      {exe, "plot", "haptic", (out / first.haptic).string(), "--format", "png",
                       "-o", prefix(layout.haptic_plot)}});
  }
}

std::vector<Step> StepsOf(const BatchOptions& options, const std::string& exe, const FilmPlan& film,
                          const FilmLayout& layout) {
  const fs::path out(layout.output_dir), tmp = fs::path(layout.state_dir) / kTempDir;
  std::vector<Step> steps;
  steps.push_back({"estimate",
                   EstimateStepKey(options),
                   {layout.camera},
                   EstimateCommand(options, exe, film.path, (tmp / layout.camera).string())});
  for (const ModelOutputs& m : layout.models) {
    std::vector<std::string> outputs = {m.haptic};
    if (!m.hjif.empty()) outputs.push_back(m.hjif);
    // haptics reads the FINAL camera path: it was renamed in when estimate succeeded.
    std::vector<std::string> command =
        HapticsCommand(options, exe, (out / layout.camera).string(), m.model,
                       (tmp / m.haptic).string(), m.hjif.empty() ? "" : (tmp / m.hjif).string());
    if (!layout.edits.empty()) command.insert(command.end(), {"--edits", layout.edits});
    steps.push_back({"haptics-" + m.model, TrackStepKey(options, m.model, layout), outputs, command});
  }
  AddReviewSteps(options, exe, film, layout, &steps);
  return steps;
}

// A step is done when its stamp has this input and key and its outputs are
// there with the contents the stamp recorded (two models of `make` write the
// same haptic file name: the other model's file is not this step's result).
bool StepIsDone(const FilmLayout& layout, const Step& step, const FilmPlan& film) {
  const auto stamp = ReadJsonFile((fs::path(layout.state_dir) / kStepsDir / (step.name + ".json")).string());
  if (!stamp || stamp->value("input_hash", "") != film.input_hash ||
      stamp->value("key", "") != step.key) {
    return false;
  }
  std::error_code ec;
  // In step.outputs' order; stamps of earlier versions have none: existence
  // is all they promise.
  const nlohmann::json hashes = stamp->value("output_hashes", nlohmann::json::array());
  for (size_t i = 0; i < step.outputs.size(); ++i) {
    const fs::path p = fs::path(layout.output_dir) / step.outputs[i];
    if (!fs::is_regular_file(p, ec)) return false;
    if (i < hashes.size() && hashes[i] != FullFileHash(p.string())) return false;
  }
  return true;
}

void RecordFailure(const fs::path& dir, const FilmPlan& film, const std::string& settings_hash,
                   const std::string& step, const std::string& reason, double seconds) {
  WriteJsonAtomic((dir / kFailedFile).string(),
                  {{"id", film.id},
                   {"path", JsonFromBytes(film.path)},
                   {"input_hash", film.input_hash},
                   {"settings_hash", settings_hash},
                   {"step", step},
                   {"reason", reason},
                   {"log", step.empty() ? "" : std::string(kLogsDir) + "/" + step + ".log"},
                   {"seconds", seconds},
                   {"host", HostName()},
                   {"finished_utc", UtcNow()}});
}

}  // namespace

const char* FilmStatusName(FilmStatus s) {
  switch (s) {
    case FilmStatus::kDone:
      return "done";
    case FilmStatus::kSkipped:
      return "skipped";
    case FilmStatus::kFailed:
      return "failed";
    case FilmStatus::kDuplicate:
      return "duplicate";
    case FilmStatus::kBusy:
      return "busy";
  }
  return "?";
}

void ReadShotQualityCounts(const std::string& camera_csv, FilmOutcome* o) {
  const std::vector<ShotQuality> shots = ReadShotQualityOfFile(camera_csv);
  if (shots.empty()) return;
  const ShotQualityCounts counts = CountShotQuality(shots);
  o->shots = counts.shots;
  o->doubtful_shots = counts.doubtful;
  o->zoom_ambiguous_shots = counts.zoom_ambiguous;
  o->lost_frames = counts.lost_frames;
}

nlohmann::json OutcomeToJson(const FilmOutcome& o) {
  nlohmann::json steps = nlohmann::json::array();
  for (const StepRecord& s : o.steps) {
    steps.push_back({{"name", s.name}, {"seconds", s.seconds}, {"reused", s.reused}});
  }
  nlohmann::json j = {{"id", o.id},
                      {"path", JsonFromBytes(o.path)},
                      {"status", FilmStatusName(o.status)},
                      {"reason", o.reason},
                      {"duplicate_of", o.duplicate_of},
                      {"seconds", o.seconds},
                      {"steps", steps},
                      {"shots", o.shots},
                      {"doubtful_shots", o.doubtful_shots},
                      {"lost_frames", o.lost_frames},
                      {"zoom_ambiguous_shots", o.zoom_ambiguous_shots}};
  if (!o.edits.empty()) j["edits"] = JsonFromBytes(o.edits);
  return j;
}

FilmOutcome OutcomeFromJson(const nlohmann::json& j) {
  FilmOutcome o;
  o.id = j.at("id").get<std::string>();
  o.path = BytesFromJson(j.at("path"));
  const std::string s = j.at("status").get<std::string>();
  for (FilmStatus st : {FilmStatus::kDone, FilmStatus::kSkipped, FilmStatus::kFailed,
                        FilmStatus::kDuplicate, FilmStatus::kBusy}) {
    if (s == FilmStatusName(st)) o.status = st;
  }
  o.reason = j.value("reason", "");
  o.duplicate_of = j.value("duplicate_of", "");
  o.seconds = j.value("seconds", 0.0);
  o.shots = j.value("shots", -1);
  o.doubtful_shots = j.value("doubtful_shots", 0);
  o.lost_frames = j.value("lost_frames", 0);
  o.zoom_ambiguous_shots = j.value("zoom_ambiguous_shots", 0);
  if (j.contains("edits")) o.edits = BytesFromJson(j.at("edits"));
  for (const auto& js : j.value("steps", nlohmann::json::array())) {
    o.steps.push_back({js.value("name", ""), js.value("seconds", 0.0), js.value("reused", false)});
  }
  return o;
}

std::vector<std::string> EstimateCommand(const BatchOptions& options, const std::string& exe,
                                         const std::string& input, const std::string& camera_csv) {
  std::vector<std::string> cmd = {exe, "estimate", input, "-o", camera_csv};
  cmd.insert(cmd.end(), options.estimate_args.begin(), options.estimate_args.end());
  return cmd;
}

std::vector<std::string> HapticsCommand(const BatchOptions& options, const std::string& exe,
                                        const std::string& camera_csv, const std::string& model,
                                        const std::string& haptic_csv, const std::string& hjif) {
  std::vector<std::string> cmd = {exe, "haptics", camera_csv, "--model", model, "-o", haptic_csv};
  if (!hjif.empty()) cmd.insert(cmd.end(), {"--hjif", hjif});
  cmd.insert(cmd.end(), options.haptics_args.begin(), options.haptics_args.end());
  return cmd;
}

bool FilmIsDone(const std::string& state_dir, const FilmPlan& film,
                const std::string& settings_hash, const std::string& output_dir,
                const std::optional<std::string>& edits_hash) {
  const auto done = ReadJsonFile((fs::path(state_dir) / kDoneFile).string());
  if (!done || done->value("input_hash", "") != film.input_hash ||
      done->value("settings_hash", "") != settings_hash) {
    return false;
  }
  if (edits_hash && done->value("edits_hash", "") != *edits_hash) return false;
  const fs::path out_dir = output_dir.empty() ? fs::path(state_dir) : fs::path(output_dir);
  std::error_code ec;
  try {
    for (const auto& out : done->value("outputs", nlohmann::json::array())) {
      const fs::path p = out_dir / BytesFromJson(out.at("file"));
      if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) != out.value("bytes", uint64_t{0})) {
        return false;
      }
    }
  } catch (const nlohmann::json::exception&) {
    return false;  // a damaged record: the film is simply done again
  }
  return true;
}

void FindEditsFile(const BatchOptions& options, const std::vector<std::string>& candidates,
                   FilmLayout* layout) {
  layout->edits.clear();
  layout->edits_hash.clear();
  const auto& args = options.haptics_args;
  const bool explicit_edits = std::any_of(args.begin(), args.end(), [](const std::string& a) {
    return a == "--edits" || a.rfind("--edits=", 0) == 0;
  });
  if (!options.use_edits || explicit_edits) return;
  std::error_code ec;
  for (const std::string& c : candidates) {
    if (fs::is_regular_file(c, ec)) {
      layout->edits = fs::absolute(c).lexically_normal().string();
      layout->edits_hash = FullFileHash(layout->edits);
      return;
    }
  }
}

FilmLayout BatchFilmLayout(const BatchOptions& options, const FilmPlan& film) {
  FilmLayout layout;
  layout.output_dir = layout.state_dir = (fs::path(options.out_dir) / film.id).string();
  layout.camera = film.stem + ".camera.csv";
  for (const std::string& model : options.models) {
    layout.models.push_back({model, film.stem + "." + model + ".haptic.csv",
                             options.hjif ? film.stem + "." + model + ".hjif" : ""});
  }
  // Beside the outputs first (where a studio serving them saves), then beside the film.
  const std::string edits_name = film.stem + ".edits.json";
  FindEditsFile(options,
                {(fs::path(layout.output_dir) / edits_name).string(),
                 (fs::path(film.path).parent_path() / (FileStem(film.path) + ".edits.json")).string()},
                &layout);
  return layout;
}

namespace {

// Runs one step into .tmp/ and renames its outputs into place; "" on
// success, else the one-line reason.
std::string RunStep(const FilmLayout& layout, const FilmPlan& film, const Step& step,
                    StepRecord* record) {
  const fs::path state(layout.state_dir), out(layout.output_dir);
  std::error_code ec;
  fs::remove(state / kStepsDir / (step.name + ".json"), ec);
  const ProcessResult r = RunProcess(step.command, (state / kLogsDir / (step.name + ".log")).string());
  record->seconds = r.seconds;
  if (!r.ok()) return step.name + ": " + r.Reason();
  for (const std::string& name : step.outputs) {
    if (!fs::is_regular_file(state / kTempDir / name, ec)) {
      return step.name + ": exited 0 but did not write " + name;
    }
  }
  nlohmann::json hashes = nlohmann::json::array();
  for (const std::string& name : step.outputs) {
    fs::rename(state / kTempDir / name, out / name, ec);
    if (ec) return step.name + ": cannot rename " + name + ": " + ec.message();
    hashes.push_back(FullFileHash((out / name).string()));
  }
  WriteJsonAtomic((state / kStepsDir / (step.name + ".json")).string(),
                  {{"input_hash", film.input_hash},
                   {"key", step.key},
                   {"seconds", r.seconds},
                   {"command", step.command},
                   {"output_hashes", hashes}});
  return "";
}

// True when the film ends before its steps (a duplicate, a precheck failure,
// up to date), with the outcome filled.
bool FinishedBeforeSteps(const BatchOptions& options, const std::string& settings_hash,
                         const FilmPlan& film, const FilmLayout& layout, FilmOutcome* outcome) {
  const fs::path dir(layout.state_dir);
  std::error_code ec;
  if (!film.duplicate_of.empty()) {
    fs::remove(dir / kDoneFile, ec);
    fs::remove(dir / kFailedFile, ec);
    WriteJsonAtomic((dir / kDuplicateFile).string(), {{"id", film.id},
                                                      {"path", JsonFromBytes(film.path)},
                                                      {"input_hash", film.input_hash},
                                                      {"duplicate_of", film.duplicate_of}});
    outcome->status = FilmStatus::kDuplicate;
    outcome->duplicate_of = film.duplicate_of;
    return true;
  }
  fs::remove(dir / kDuplicateFile, ec);
  if (!film.precheck_error.empty()) {
    fs::remove(dir / kDoneFile, ec);
    RecordFailure(dir, film, settings_hash, "", film.precheck_error, 0.0);
    outcome->reason = film.precheck_error;
    return true;
  }
  if (!options.force &&
      FilmIsDone(dir.string(), film, settings_hash, layout.output_dir, layout.edits_hash)) {
    fs::remove(dir / kFailedFile, ec);
    outcome->status = FilmStatus::kSkipped;
    ReadShotQualityCounts((fs::path(layout.output_dir) / layout.camera).string(), outcome);
    return true;
  }
  return false;
}

void WriteDoneRecord(const BatchOptions& options, const std::string& settings_hash,
                     const FilmPlan& film, const FilmLayout& layout, const FilmOutcome& outcome,
                     const nlohmann::json& outputs) {
  nlohmann::json done = {{"id", film.id},
                         {"path", JsonFromBytes(film.path)},
                         {"stem", JsonFromBytes(film.stem)},
                         {"input_hash", film.input_hash},
                         {"size_bytes", film.size_bytes},
                         {"settings_hash", settings_hash},
                         {"settings", SettingsJson(options)},
                         {"outputs", outputs},
                         {"steps", OutcomeToJson(outcome)["steps"]},
                         {"seconds", outcome.seconds},
                         {"host", HostName()},
                         {"finished_utc", UtcNow()}};
  if (!layout.edits.empty()) {  // only then, so records without edits stay as they were
    done["edits"] = JsonFromBytes(layout.edits);
    done["edits_hash"] = layout.edits_hash;
  }
  WriteJsonAtomic((fs::path(layout.state_dir) / kDoneFile).string(), done);
}

}  // namespace

FilmOutcome RunFilm(const BatchOptions& options, const std::string& step_exe,
                    const std::string& settings_hash, const FilmPlan& film,
                    const FilmLayout& layout, FilmObserver* observer) {
  const auto t0 = Clock::now();
  FilmOutcome outcome;
  outcome.id = film.id;
  outcome.path = film.path;
  outcome.edits = layout.edits;
  const fs::path dir(layout.state_dir), out_dir(layout.output_dir);
  std::error_code ec;
  for (const fs::path& d : {dir, out_dir}) {
    fs::create_directories(d, ec);
    if (ec) {
      outcome.reason = d.string() + ": cannot create folder: " + ec.message();
      return outcome;
    }
  }
  FilmLock lock(dir.string());
  if (!lock.locked()) {
    outcome.status = FilmStatus::kBusy;
    outcome.reason = "being processed by another batch process";
    return outcome;
  }
  CleanFilmTemp(dir.string());
  if (FinishedBeforeSteps(options, settings_hash, film, layout, &outcome)) {
    outcome.seconds = SecondsSince(t0);
    return outcome;
  }

  // From here on the film is (re)done: whatever done.json said is stale.
  fs::remove(dir / kDoneFile, ec);
  fs::remove(dir / kFailedFile, ec);
  if (options.force) fs::remove_all(dir / kStepsDir, ec);
  for (const char* sub : {kTempDir, kStepsDir, kLogsDir}) fs::create_directories(dir / sub, ec);

  nlohmann::json outputs = nlohmann::json::array();
  for (const Step& step : StepsOf(options, step_exe, film, layout)) {
    StepRecord record{step.name, 0.0, StepIsDone(layout, step, film)};
    if (observer) {
      observer->StepStarted(step.name, (dir / kLogsDir / (step.name + ".log")).string(),
                            record.reused);
    }
    if (!record.reused) {
      const std::string reason = RunStep(layout, film, step, &record);
      if (!reason.empty()) {
        outcome.steps.push_back(record);
        outcome.reason = reason;
        outcome.seconds = SecondsSince(t0);
        RecordFailure(dir, film, settings_hash, step.name, reason, outcome.seconds);
        fs::remove_all(dir / kTempDir, ec);
        return outcome;
      }
    }
    for (const std::string& name : step.outputs) {
      outputs.push_back({{"file", JsonFromBytes(name)},
                         {"step", step.name},
                         {"bytes", fs::file_size(out_dir / name, ec)},
                         {"hash", FullFileHash((out_dir / name).string())}});
    }
    outcome.steps.push_back(record);
  }
  fs::remove_all(dir / kTempDir, ec);
  outcome.status = FilmStatus::kDone;
  ReadShotQualityCounts((out_dir / layout.camera).string(), &outcome);
  outcome.seconds = SecondsSince(t0);
  WriteDoneRecord(options, settings_hash, film, layout, outcome, outputs);
  return outcome;
}

FilmOutcome ProcessFilm(const BatchOptions& options, const std::string& step_exe,
                        const std::string& settings_hash, const FilmPlan& film) {
  return RunFilm(options, step_exe, settings_hash, film, BatchFilmLayout(options, film));
}

}  // namespace hapcine::batch
