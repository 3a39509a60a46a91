#include "batch/film_runner.h"


#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "batch/content_hash.h"
#include "batch/json_bytes.h"
#include "batch/state_files.h"
#include "batch/subprocess.h"
#include "core/error.h"

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
  std::vector<std::string> outputs;  // file names inside the film folder
  std::vector<std::string> command;  // writes those names inside .tmp/
};

std::vector<Step> StepsOf(const BatchOptions& options, const std::string& exe, const FilmPlan& film,
                          const fs::path& dir) {
  const fs::path tmp = dir / kTempDir;
  const std::string camera = film.stem + ".camera.csv";
  std::vector<Step> steps;
  steps.push_back({"estimate",
                   EstimateStepKey(options),
                   {camera},
                   EstimateCommand(options, exe, film.path, (tmp / camera).string())});
  for (const std::string& model : options.models) {
    const std::string haptic = film.stem + "." + model + ".haptic.csv";
    const std::string hjif = film.stem + "." + model + ".hjif";
    // haptics reads the FINAL camera path: it was renamed in when estimate succeeded.
    steps.push_back({"haptics-" + model,
                     HapticsStepKey(options, model),
                     {haptic, hjif},
                     HapticsCommand(options, exe, (dir / camera).string(), model,
                                    (tmp / haptic).string(), (tmp / hjif).string())});
  }
  return steps;
}

bool StepIsDone(const fs::path& dir, const Step& step, const FilmPlan& film) {
  const auto stamp = ReadJsonFile((dir / kStepsDir / (step.name + ".json")).string());
  if (!stamp || stamp->value("input_hash", "") != film.input_hash ||
      stamp->value("key", "") != step.key) {
    return false;
  }
  std::error_code ec;
  for (const std::string& out : step.outputs) {
    if (!fs::is_regular_file(dir / out, ec)) return false;
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
  std::ifstream in(camera_csv);
  std::string line;
  const std::string key = "# shot_quality.";
  while (std::getline(in, line) && line.rfind("#", 0) == 0) {
    if (line.rfind(key, 0) != 0) continue;
    o->shots = std::max(o->shots, 0) + 1;
    if (line.find(" doubtful:1") != std::string::npos) ++o->doubtful_shots;
    const size_t lost = line.find(" lost:");
    if (lost != std::string::npos) o->lost_frames += std::atoi(line.c_str() + lost + 6);
  }
}

nlohmann::json OutcomeToJson(const FilmOutcome& o) {
  nlohmann::json steps = nlohmann::json::array();
  for (const StepRecord& s : o.steps) {
    steps.push_back({{"name", s.name}, {"seconds", s.seconds}, {"reused", s.reused}});
  }
  return {{"id", o.id},
          {"path", JsonFromBytes(o.path)},
          {"status", FilmStatusName(o.status)},
          {"reason", o.reason},
          {"duplicate_of", o.duplicate_of},
          {"seconds", o.seconds},
          {"steps", steps},
          {"shots", o.shots},
          {"doubtful_shots", o.doubtful_shots},
          {"lost_frames", o.lost_frames}};
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
  std::vector<std::string> cmd = {exe,  "haptics",  camera_csv, "--model", model,
                                  "-o", haptic_csv, "--hjif",   hjif};
  cmd.insert(cmd.end(), options.haptics_args.begin(), options.haptics_args.end());
  return cmd;
}

bool FilmIsDone(const std::string& film_dir, const FilmPlan& film,
                const std::string& settings_hash) {
  const auto done = ReadJsonFile((fs::path(film_dir) / kDoneFile).string());
  if (!done || done->value("input_hash", "") != film.input_hash ||
      done->value("settings_hash", "") != settings_hash) {
    return false;
  }
  std::error_code ec;
  try {
    for (const auto& out : done->value("outputs", nlohmann::json::array())) {
      const fs::path p = fs::path(film_dir) / BytesFromJson(out.at("file"));
      if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) != out.value("bytes", uint64_t{0})) {
        return false;
      }
    }
  } catch (const nlohmann::json::exception&) {
    return false;  // a damaged record: the film is simply done again
  }
  return true;
}

FilmOutcome ProcessFilm(const BatchOptions& options, const std::string& step_exe,
                        const std::string& settings_hash, const FilmPlan& film) {
  const auto t0 = Clock::now();
  FilmOutcome outcome;
  outcome.id = film.id;
  outcome.path = film.path;
  const fs::path dir = fs::path(options.out_dir) / film.id;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    outcome.reason = dir.string() + ": cannot create folder: " + ec.message();
    return outcome;
  }
  FilmLock lock(dir.string());
  if (!lock.locked()) {
    outcome.status = FilmStatus::kBusy;
    outcome.reason = "being processed by another batch process";
    return outcome;
  }
  CleanFilmTemp(dir.string());

  if (!film.duplicate_of.empty()) {
    fs::remove(dir / kDoneFile, ec);
    fs::remove(dir / kFailedFile, ec);
    WriteJsonAtomic((dir / kDuplicateFile).string(), {{"id", film.id},
                                                      {"path", JsonFromBytes(film.path)},
                                                      {"input_hash", film.input_hash},
                                                      {"duplicate_of", film.duplicate_of}});
    outcome.status = FilmStatus::kDuplicate;
    outcome.duplicate_of = film.duplicate_of;
    outcome.seconds = SecondsSince(t0);
    return outcome;
  }
  fs::remove(dir / kDuplicateFile, ec);

  if (!film.precheck_error.empty()) {
    fs::remove(dir / kDoneFile, ec);
    RecordFailure(dir, film, settings_hash, "", film.precheck_error, 0.0);
    outcome.reason = film.precheck_error;
    outcome.seconds = SecondsSince(t0);
    return outcome;
  }

  if (!options.force && FilmIsDone(dir.string(), film, settings_hash)) {
    fs::remove(dir / kFailedFile, ec);
    outcome.status = FilmStatus::kSkipped;
    ReadShotQualityCounts((dir / (film.stem + ".camera.csv")).string(), &outcome);
    outcome.seconds = SecondsSince(t0);
    return outcome;
  }

  // From here on the film is (re)done: whatever done.json said is stale.
  fs::remove(dir / kDoneFile, ec);
  fs::remove(dir / kFailedFile, ec);
  if (options.force) fs::remove_all(dir / kStepsDir, ec);
  fs::create_directories(dir / kTempDir, ec);
  fs::create_directories(dir / kStepsDir, ec);
  fs::create_directories(dir / kLogsDir, ec);

  nlohmann::json outputs = nlohmann::json::array();
  for (const Step& step : StepsOf(options, step_exe, film, dir)) {
    StepRecord record{step.name, 0.0, false};
    if (StepIsDone(dir, step, film)) {
      record.reused = true;
    } else {
      fs::remove(dir / kStepsDir / (step.name + ".json"), ec);
      const ProcessResult r =
          RunProcess(step.command, (dir / kLogsDir / (step.name + ".log")).string());
      record.seconds = r.seconds;
      std::string reason;
      if (!r.ok()) {
        reason = step.name + ": " + r.Reason();
      } else {
        for (const std::string& out : step.outputs) {
          if (!fs::is_regular_file(dir / kTempDir / out, ec)) {
            reason = step.name + ": exited 0 but did not write " + out;
            break;
          }
        }
      }
      if (!reason.empty()) {
        outcome.steps.push_back(record);
        outcome.reason = reason;
        outcome.seconds = SecondsSince(t0);
        RecordFailure(dir, film, settings_hash, step.name, reason, outcome.seconds);
        fs::remove_all(dir / kTempDir, ec);
        return outcome;
      }
      for (const std::string& out : step.outputs) {
        fs::rename(dir / kTempDir / out, dir / out, ec);
        if (ec) {
          outcome.reason = step.name + ": cannot rename " + out + ": " + ec.message();
          RecordFailure(dir, film, settings_hash, step.name, outcome.reason, SecondsSince(t0));
          fs::remove_all(dir / kTempDir, ec);
          return outcome;
        }
      }
      WriteJsonAtomic((dir / kStepsDir / (step.name + ".json")).string(),
                      {{"input_hash", film.input_hash},
                       {"key", step.key},
                       {"seconds", r.seconds},
                       {"command", step.command}});
    }
    for (const std::string& out : step.outputs) {
      outputs.push_back({{"file", JsonFromBytes(out)},
                         {"step", step.name},
                         {"bytes", fs::file_size(dir / out, ec)},
                         {"hash", FullFileHash((dir / out).string())}});
    }
    outcome.steps.push_back(record);
  }
  fs::remove_all(dir / kTempDir, ec);
  outcome.status = FilmStatus::kDone;
  ReadShotQualityCounts((dir / (film.stem + ".camera.csv")).string(), &outcome);
  outcome.seconds = SecondsSince(t0);
  nlohmann::json steps = OutcomeToJson(outcome)["steps"];
  WriteJsonAtomic((dir / kDoneFile).string(), {{"id", film.id},
                                               {"path", JsonFromBytes(film.path)},
                                               {"stem", JsonFromBytes(film.stem)},
                                               {"input_hash", film.input_hash},
                                               {"size_bytes", film.size_bytes},
                                               {"settings_hash", settings_hash},
                                               {"settings", SettingsJson(options)},
                                               {"outputs", outputs},
                                               {"steps", steps},
                                               {"seconds", outcome.seconds},
                                               {"host", HostName()},
                                               {"finished_utc", UtcNow()}});
  return outcome;
}

}  // namespace hapcine::batch
