#include "batch/batch.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "batch/progress.h"
#include "batch/state_files.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine::batch {
namespace fs = std::filesystem;

int BatchSummary::Count(FilmStatus s) const {
  return static_cast<int>(std::count_if(films.begin(), films.end(),
                                        [s](const FilmOutcome& f) { return f.status == s; }));
}

int BatchSummary::ExitCode() const {
  return Count(FilmStatus::kFailed) + Count(FilmStatus::kBusy) == 0 ? 0 : 1;
}

nlohmann::json BatchSummary::ToJson() const {
  nlohmann::json films_json = nlohmann::json::array();
  for (const FilmOutcome& f : films) films_json.push_back(OutcomeToJson(f));
  nlohmann::json counts;
  for (FilmStatus s : {FilmStatus::kDone, FilmStatus::kSkipped, FilmStatus::kFailed,
                       FilmStatus::kDuplicate, FilmStatus::kBusy}) {
    counts[FilmStatusName(s)] = Count(s);
  }
  return {{"hapcine_version", HapcineVersion()},
          {"library", library},
          {"out_dir", out_dir},
          {"settings_hash", settings_hash},
          {"shard", {{"index", shard_index}, {"count", shard_count}}},
          {"jobs", jobs},
          {"started_utc", started_utc},
          {"wall_seconds", wall_seconds},
          {"total", films.size()},
          {"counts", counts},
          {"films", films_json}};
}

BatchSummary BatchSummary::FromJson(const nlohmann::json& j) {
  BatchSummary s;
  s.library = j.value("library", "");
  s.out_dir = j.value("out_dir", "");
  s.settings_hash = j.value("settings_hash", "");
  s.shard_index = j.at("shard").value("index", 0);
  s.shard_count = j.at("shard").value("count", 1);
  s.jobs = j.value("jobs", 1);
  s.started_utc = j.value("started_utc", "");
  s.wall_seconds = j.value("wall_seconds", 0.0);
  for (const auto& f : j.at("films")) s.films.push_back(OutcomeFromJson(f));
  return s;
}

std::string BatchSummary::ToText() const {
  std::ostringstream out;
  out << "hapcine batch " << HapcineVersion() << "  library: " << library << "\n"
      << "output: " << out_dir;
  if (shard_count > 1) out << "  shard " << shard_index << "/" << shard_count;
  out << "\nstarted " << started_utc << ", wall time " << std::fixed << std::setprecision(1)
      << wall_seconds << " s, " << jobs << " job(s)\n"
      << films.size() << " films: " << Count(FilmStatus::kDone) << " done, "
      << Count(FilmStatus::kSkipped) << " skipped (up to date), " << Count(FilmStatus::kFailed)
      << " failed, " << Count(FilmStatus::kDuplicate) << " duplicate";
  if (Count(FilmStatus::kBusy) > 0) out << ", " << Count(FilmStatus::kBusy) << " busy elsewhere";
  // Where the time went: steps run (not reused), by kind (estimate, haptics-<model>).
  std::map<std::string, std::pair<int, double>> by_step;
  for (const FilmOutcome& f : films) {
    for (const StepRecord& st : f.steps) {
      if (st.reused) continue;
      by_step[st.name].first += 1;
      by_step[st.name].second += st.seconds;
    }
  }
  if (!by_step.empty()) {
    out << "\nsteps run:";
    const char* sep = " ";
    for (const auto& [name, n_s] : by_step) {
      out << sep << name << " " << n_s.first << "x, " << n_s.second << " s (mean "
          << n_s.second / n_s.first << " s)";
      sep = "; ";
    }
  }
  out << "\n\n";
  for (const FilmOutcome& f : films) {
    out << std::left << std::setw(9) << FilmStatusName(f.status) << " " << std::right
        << std::setw(7) << std::setprecision(1) << f.seconds << " s  " << f.id;
    if (f.status == FilmStatus::kDuplicate) out << "  duplicate of " << f.duplicate_of;
    if (f.doubtful_shots > 0)
      out << "  " << f.doubtful_shots << " of " << f.shots << " shots doubtful, " << f.lost_frames
          << " frames lost";
    if (f.zoom_ambiguous_shots > 0)
      out << "  " << f.zoom_ambiguous_shots << " of " << f.shots << " shots zoom ambiguous";
    if (!f.edits.empty()) out << "  edits " << f.edits;
    if (!f.reason.empty()) out << "  " << f.reason;
    out << "\n";
  }
  return out.str();
}

void WriteSummary(const BatchSummary& summary) {
  WriteJsonAtomic((fs::path(summary.out_dir) / "summary.json").string(), summary.ToJson());
  AtomicFile text((fs::path(summary.out_dir) / "summary.txt").string());
  text.stream() << summary.ToText();
  text.Commit();
}

namespace {

// The summary's header: what runs, where, on how many workers, since when.
BatchSummary SummaryHeader(const BatchOptions& options) {
  BatchSummary summary;
  summary.library = options.library;
  summary.out_dir = options.out_dir;
  summary.shard_index = options.shard_index;
  summary.shard_count = options.shard_count;
  summary.jobs = options.ResolvedJobs();
  summary.started_utc = UtcNow();
  return summary;
}

// OUT_DIR/.hapcine (kStateDir) and its shards/ folder, created, with the
// temporary files of dead runs removed; returns the state folder.
fs::path PrepareStateFolder(const std::string& out_dir) {
  std::error_code ec;
  const fs::path state = fs::path(out_dir) / kStateDir;
  fs::create_directories(state / "shards", ec);
  if (ec) throw Error(out_dir, "cannot create output folder: " + ec.message());
  CleanDeadTempFiles(out_dir);
  CleanDeadTempFiles(state.string());
  CleanDeadTempFiles((state / "shards").string());
  return state;
}

// The plan's films of shard `shard_index`, originals first, so a duplicate
// is recorded after what it points to.
std::vector<const FilmPlan*> FilmsOfShard(const BatchPlan& plan, int shard_index) {
  std::vector<const FilmPlan*> mine;
  for (const FilmPlan& f : plan.films) {
    if (f.shard == shard_index) mine.push_back(&f);
  }
  std::stable_partition(mine.begin(), mine.end(),
                        [](const FilmPlan* f) { return f->duplicate_of.empty(); });
  return mine;
}

ProgressReporter::Mode ReporterMode(BatchOptions::Progress progress) {
  switch (progress) {
    case BatchOptions::Progress::kAuto:
      return ProgressModeFor(false);
    case BatchOptions::Progress::kBar:
      return ProgressReporter::Mode::kBar;
    case BatchOptions::Progress::kLines:
      return ProgressReporter::Mode::kLines;
    case BatchOptions::Progress::kQuiet:
      break;
  }
  return ProgressReporter::Mode::kQuiet;
}

// One film's steps; an exception (e.g. an unwritable output folder) is the
// film's failure, not the batch's.
FilmOutcome ProcessFilmOrFail(const BatchOptions& options, const std::string& step_exe,
                              const std::string& settings_hash, const FilmPlan& film,
                              ProgressReporter& progress) {
  FilmOutcome o;
  progress.Started(film.id);
  try {
    o = ProcessFilm(options, step_exe, settings_hash, film);
  } catch (const std::exception& e) {
    o.id = film.id;
    o.path = film.path;
    o.status = FilmStatus::kFailed;
    o.reason = e.what();
  }
  const bool reused = o.status != FilmStatus::kDone && o.status != FilmStatus::kFailed;
  progress.Finished(o.id, FilmStatusName(o.status), o.seconds, reused, o.reason);
  return o;
}

// The films on `workers` threads, each taking the next film left, while
// this thread ticks the progress every second; outcomes in `films` order.
std::vector<FilmOutcome> ProcessFilmsInParallel(const BatchOptions& options, const std::string& step_exe,
                                                const std::string& settings_hash,
                                                const std::vector<const FilmPlan*>& films, int workers,
                                                ProgressReporter& progress) {
  std::vector<FilmOutcome> outcomes(films.size());
  std::atomic<size_t> next{0};
  std::mutex mu;
  std::condition_variable cv;
  int running_workers = workers;
  auto worker = [&]() {
    for (size_t i = next++; i < films.size(); i = next++)
      outcomes[i] = ProcessFilmOrFail(options, step_exe, settings_hash, *films[i], progress);
    std::lock_guard<std::mutex> lock(mu);
    --running_workers;
    cv.notify_all();
  };
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w) threads.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mu);
    while (!cv.wait_for(lock, std::chrono::seconds(1), [&] { return running_workers == 0; })) {
      progress.Tick();
    }
  }
  for (std::thread& t : threads) t.join();
  return outcomes;
}

// The outcomes in plan (path) order, whatever order the workers finished in.
std::vector<FilmOutcome> InPathOrder(const std::vector<const FilmPlan*>& films,
                                     const std::vector<FilmOutcome>& outcomes) {
  std::vector<size_t> order(films.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return films[a]->path < films[b]->path; });
  std::vector<FilmOutcome> sorted;
  for (size_t i : order) sorted.push_back(outcomes[i]);
  return sorted;
}

// A shard's summary goes to the state folder (the submitter merges them);
// an unsharded run writes summary.json and summary.txt.
void WriteRunSummary(const BatchOptions& options, const BatchSummary& summary) {
  if (options.sharded()) {
    WriteJsonAtomic(ShardSummaryPath(options.out_dir, options.shard_index, options.shard_count),
                    summary.ToJson());
  } else {
    WriteSummary(summary);
  }
}

}  // namespace

BatchSummary RunLocalBatch(const BatchOptions& options) {
  options.Check();
  const auto t0 = std::chrono::steady_clock::now();
  BatchSummary summary = SummaryHeader(options);
  const fs::path state = PrepareStateFolder(options.out_dir);

  const BatchPlan plan = MakePlan(options);
  summary.settings_hash = plan.settings_hash;
  // Shards share one plan.json written by the submitter; an unsharded run
  // writes its own (status reads it).
  if (!options.sharded()) WriteJsonAtomic((state / "plan.json").string(), PlanToJson(plan));
  const std::vector<const FilmPlan*> mine = FilmsOfShard(plan, options.shard_index);

  const ProgressReporter::Mode mode = ReporterMode(options.progress);
  const std::string step_exe = options.ResolvedStepExe();
  const int workers = std::max(1, std::min<int>(summary.jobs, static_cast<int>(mine.size())));
  ProgressReporter progress(std::cerr, mode, static_cast<int>(mine.size()), workers);
  const std::vector<FilmOutcome> outcomes =
      ProcessFilmsInParallel(options, step_exe, plan.settings_hash, mine, workers, progress);
  progress.Close();

  summary.films = InPathOrder(mine, outcomes);
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WriteRunSummary(options, summary);
  return summary;
}

std::string BatchStatus::ToText() const {
  std::ostringstream out;
  out << total << " films: " << done << " done, " << failed << " failed, " << duplicate
      << " duplicate, " << running << " running, " << pending << " pending\n";
  for (const auto& [id, reason] : failures) out << "  failed " << id << ": " << reason << "\n";
  for (const std::string& t : slurm_tasks) out << "  slurm " << t << "\n";
  return out.str();
}

BatchStatus ReadBatchStatus(const std::string& out_dir) {
  const fs::path plan_path = fs::path(out_dir) / kStateDir / "plan.json";
  const auto plan_json = ReadJsonFile(plan_path.string());
  if (!plan_json) throw Error(plan_path.string(), "no batch state here (missing or unreadable)");
  BatchPlan plan;
  try {
    plan = PlanFromJson(*plan_json);
  } catch (const std::exception& e) {
    throw Error(plan_path.string(), std::string("malformed plan: ") + e.what());
  }
  BatchStatus status;
  for (const FilmPlan& f : plan.films) {
    ++status.total;
    const fs::path dir = fs::path(out_dir) / f.id;
    if (!f.duplicate_of.empty() && fs::exists(dir / kDuplicateFile)) {
      ++status.duplicate;
    } else if (FilmIsLocked(dir.string())) {
      ++status.running;
    } else if (f.duplicate_of.empty() && FilmIsDone(dir.string(), f, plan.settings_hash)) {
      ++status.done;
    } else if (const auto failed = ReadJsonFile((dir / kFailedFile).string());
               failed && failed->value("input_hash", "") == f.input_hash &&
               failed->value("settings_hash", "") == plan.settings_hash) {
      ++status.failed;
      status.failures.emplace_back(f.id, failed->value("reason", ""));
    } else {
      ++status.pending;
    }
  }
  const fs::path slurm = fs::path(out_dir) / "slurm";
  for (int i = 0; i < plan.shard_count && plan.shard_count > 1; ++i) {
    std::ifstream in(slurm / ("task-" + std::to_string(i) + ".status"));
    std::string line;
    if (in && std::getline(in, line)) {
      status.slurm_tasks.push_back("task " + std::to_string(i) + ": " + line);
    } else {
      status.slurm_tasks.push_back("task " + std::to_string(i) + ": no exit status yet");
    }
  }
  return status;
}

}  // namespace hapcine::batch
