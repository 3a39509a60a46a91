#include "batch/slurm.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "batch/library.h"
#include "batch/progress.h"
#include "batch/state_files.h"
#include "batch/subprocess.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine::batch {
namespace fs = std::filesystem;
namespace {

std::string FindInPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path p = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  throw Error(program, "not found in PATH (is Slurm installed on this machine?)");
}

std::string JoinQuoted(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : " ") + ShellQuote(w);
  return s;
}

std::string Join(const std::vector<std::string>& words, const std::string& sep) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : sep) + w;
  return s;
}

std::string StatusPath(const std::string& out_dir, int task) {
  return (fs::path(out_dir) / "slurm" / ("task-" + std::to_string(task) + ".status")).string();
}

// The job's tasks still known to Slurm (pending or running), or -1 if squeue
// could not be asked.
int TasksInQueue(const std::string& job_id, const std::string& log) {
  std::string squeue;
  try {
    squeue = FindInPath("squeue");
  } catch (const Error&) {
    return -1;
  }
  const ProcessResult r = RunProcess({squeue, "-h", "-r", "-j", job_id, "-o", "%i"}, log);
  if (!r.ok()) {
    // An unknown (finished and purged) job id is an error for squeue.
    return r.last_line.find("Invalid job id") != std::string::npos ? 0 : -1;
  }
  std::ifstream in(log);
  int n = 0;
  std::string line;
  while (std::getline(in, line)) n += line.find_first_not_of(" \t") != std::string::npos;
  return n;
}

}  // namespace

void SlurmOptions::Check() const {
  if (shards < 1) throw UsageError("--shards must be >= 1");
  if (!(poll_s > 0)) throw UsageError("poll interval must be > 0");
  if (!(wait_timeout_s >= 0 && std::isfinite(wait_timeout_s))) throw UsageError("--wait-timeout must be >= 0");
}

std::string ShellQuote(const std::string& word) {
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string SlurmJobScript(const BatchOptions& options, const SlurmOptions& slurm,
                           const std::string& manifest, int shards) {
  const std::string batch_exe = slurm.batch_exe.empty() ? SelfExecutable() : slurm.batch_exe;
  std::vector<std::string> cmd = {batch_exe,
                                  "batch",
                                  manifest,
                                  "-o",
                                  fs::absolute(options.out_dir).lexically_normal().string(),
                                  "--jobs",
                                  std::to_string(options.ResolvedJobs()),
                                  "--models",
                                  Join(options.models, ","),
                                  "--hapcine-exe",
                                  options.ResolvedStepExe(),
                                  "--progress",
                                  "lines"};
  if (!options.estimate_args.empty()) {
    cmd.push_back("--estimate-args");
    cmd.push_back(JoinQuoted(options.estimate_args));
  }
  if (!options.haptics_args.empty()) {
    cmd.push_back("--haptics-args");
    cmd.push_back(JoinQuoted(options.haptics_args));
  }
  if (options.force) cmd.push_back("--force");
  if (!options.use_edits) cmd.push_back("--no-edits");
  const std::string status_dir =
      (fs::absolute(options.out_dir).lexically_normal() / "slurm").string();
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# hapcine batch: one Slurm array task per shard of the library.\n"
    << "# Written by `hapcine batch --slurm`; submitted with --array=0-" << shards - 1 << ".\n"
    << "set -u\n"
    << "i=\"${SLURM_ARRAY_TASK_ID:?not run as a Slurm array task}\"\n"
    << JoinQuoted(cmd) << " --shard \"$i/" << shards << "\"\n"
    << "rc=$?\n"
    << "# The task's own exit status, written atomically (the submitter polls it).\n"
    << "st=" << ShellQuote(status_dir) << "/task-$i.status\n"
    << "printf '%s %s\\n' \"$rc\" \"${SLURM_ARRAY_JOB_ID:-?}\" > \"$st.tmp-$$\" && mv -f "
       "\"$st.tmp-$$\" \"$st\"\n"
    << "exit $rc\n";
  return s.str();
}

BatchSummary MergeShardSummaries(const BatchOptions& options, const BatchPlan& plan) {
  BatchSummary merged;
  merged.library = options.library;
  merged.out_dir = options.out_dir;
  merged.settings_hash = plan.settings_hash;
  merged.jobs = options.ResolvedJobs();
  for (int i = 0; i < plan.shard_count; ++i) {
    const auto j = ReadJsonFile(ShardSummaryPath(options.out_dir, i, plan.shard_count));
    std::vector<FilmOutcome> films;
    bool ok = false;
    if (j) {
      try {
        films = BatchSummary::FromJson(*j).films;
        ok = true;
      } catch (const std::exception&) {
        ok = false;
      }
    }
    if (!ok) {
      for (const FilmPlan& f : plan.films) {
        if (f.shard != i) continue;
        FilmOutcome o;
        o.id = f.id;
        o.path = f.path;
        o.status = FilmStatus::kFailed;
        o.reason = "slurm task " + std::to_string(i) + " wrote no summary (see slurm/task-" +
                   std::to_string(i) + ".log)";
        films.push_back(o);
      }
    }
    merged.films.insert(merged.films.end(), films.begin(), films.end());
  }
  std::sort(merged.films.begin(), merged.films.end(),
            [](const FilmOutcome& a, const FilmOutcome& b) { return a.path < b.path; });
  return merged;
}

namespace {

// The library frozen into `manifest` (tasks read it, not the folder).
void FreezeLibrary(const std::string& library, const std::string& manifest) {
  const std::vector<std::string> films = ListLibrary(library);
  AtomicFile m(manifest);
  m.stream() << "# frozen by hapcine batch --slurm from " << library << "\n";
  for (const std::string& p : films) {
    if (p.find('\n') != std::string::npos) continue;  // cannot be listed in a manifest
    m.stream() << p << "\n";
  }
  m.Commit();
}

// The plan in as many shards as wanted but no more than there are original
// films (duplicates need no task); sets options->shard_count.
BatchPlan PlanInShards(BatchOptions* options, int wanted_shards) {
  options->shard_count = 1;
  int originals = 0;
  for (const FilmPlan& f : MakePlan(*options).films) originals += f.duplicate_of.empty();
  options->shard_count = std::max(1, std::min(wanted_shards, originals));
  return MakePlan(*options);
}

// Forget what an earlier submission reported, and the temporaries of a
// status its task was killed in the middle of writing (scancel between the
// job script's printf and mv).
void ForgetEarlierSubmission(const fs::path& slurm_dir, const fs::path& state) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(slurm_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".status" || name.find(".status.tmp-") != std::string::npos)
      fs::remove(entry.path(), ec);
  }
  for (const auto& entry : fs::directory_iterator(state / "shards", ec)) {
    fs::remove(entry.path(), ec);
  }
}

void WriteJobScript(const std::string& job, const BatchOptions& options, const SlurmOptions& slurm,
                    const std::string& manifest) {
  std::error_code ec;
  AtomicFile script(job);
  script.stream() << SlurmJobScript(options, slurm, manifest, options.shard_count);
  script.Commit();
  fs::permissions(job, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read, ec);
}

// `sbatch` of job.sh as an array of options.shard_count tasks; the job id.
std::string SubmitJobArray(const std::string& sbatch, const BatchOptions& options,
                           const SlurmOptions& slurm, const fs::path& slurm_dir,
                           const std::string& job) {
  std::vector<std::string> cmd = {sbatch,
                                  "--parsable",
                                  "--array=0-" + std::to_string(options.shard_count - 1),
                                  "--job-name=hapcine-batch",
                                  "--output=" + (slurm_dir / "task-%a.log").string(),
                                  "--cpus-per-task=" + std::to_string(options.ResolvedJobs())};
  cmd.insert(cmd.end(), slurm.sbatch_args.begin(), slurm.sbatch_args.end());
  cmd.push_back(job);
  const std::string sbatch_log = (slurm_dir / "sbatch.log").string();
  const ProcessResult r = RunProcess(cmd, sbatch_log);
  if (!r.ok()) throw Error("sbatch", "refused the job: " + r.Reason());
  std::string job_id = r.last_line.substr(0, r.last_line.find(';'));
  if (job_id.empty() || job_id.find_first_not_of("0123456789") != std::string::npos) {
    throw Error("sbatch", "unexpected output: " + r.last_line);
  }
  return job_id;
}

int FinishedTasks(const std::string& out, int shards) {
  std::error_code ec;
  int finished = 0;
  for (int i = 0; i < shards; ++i) finished += fs::exists(StatusPath(out, i), ec);
  return finished;
}

// One line of the job's progress, from the films' state files.
void PrintJobProgress(const std::string& out, const std::string& job_id, int finished, int shards) {
  try {
    const BatchStatus st = ReadBatchStatus(out);
    std::cerr << "batch: job " << job_id << ": " << finished << "/" << shards
              << " tasks finished; films " << st.done << " done, " << st.failed << " failed, "
              << st.running << " running, " << st.pending << " pending\n";
  } catch (const Error&) {
  }
}

// Waits for every task's status file: false when --wait-timeout ran out.
// Status files first (cheap, written by every task that finished), squeue
// every few seconds to notice tasks that died without one.
bool WaitForTasks(const std::string& out, const std::string& job_id, int shards,
                  const SlurmOptions& slurm, std::chrono::steady_clock::time_point t0) {
  const std::string squeue_log = (fs::path(out) / "slurm" / "squeue.log").string();
  auto last_squeue = std::chrono::steady_clock::now();
  auto last_report = last_squeue;
  int gone_polls = 0;
  while (true) {
    const int finished = FinishedTasks(out, shards);
    if (finished == shards) return true;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_squeue > std::chrono::seconds(3)) {
      last_squeue = now;
      const int queued = TasksInQueue(job_id, squeue_log);
      // Gone from the queue twice in a row but status files missing: died.
      gone_polls = queued == 0 ? gone_polls + 1 : 0;
      if (gone_polls >= 2) {
        std::cerr << "batch: job " << job_id << " left the queue with " << shards - finished
                  << " task(s) that wrote no exit status\n";
        return true;
      }
    }
    if (now - last_report > std::chrono::seconds(10)) {
      last_report = now;
      PrintJobProgress(out, job_id, finished, shards);
    }
    const double waited = std::chrono::duration<double>(now - t0).count();
    if (slurm.wait_timeout_s > 0 && waited > slurm.wait_timeout_s) {
      std::cerr << "batch: stopped waiting after " << FormatDuration(waited) << "; job " << job_id
                << " keeps running (hapcine batch --status)\n";
      return false;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(slurm.poll_s));
  }
}

// 0 when every task wrote exit status 0, else 1.
int TasksExitCode(const std::string& out, int shards) {
  int exit_code = 0;
  for (int i = 0; i < shards; ++i) {
    std::ifstream in(StatusPath(out, i));
    int rc = -1;
    if (!(in >> rc) || rc != 0) exit_code = 1;
  }
  return exit_code;
}

void PrintJobTotals(const BatchSummary& merged, const std::string& job_id, const fs::path& out) {
  std::cerr << "batch: Slurm job " << job_id << " finished in "
            << FormatDuration(merged.wall_seconds) << ": " << merged.Count(FilmStatus::kDone)
            << " done, " << merged.Count(FilmStatus::kSkipped) << " skipped, "
            << merged.Count(FilmStatus::kFailed) << " failed, "
            << merged.Count(FilmStatus::kDuplicate) << " duplicate; see "
            << (out / "summary.txt").string() << "\n";
}

}  // namespace

int SubmitSlurmBatch(const BatchOptions& base_options, const SlurmOptions& slurm) {
  base_options.Check();
  slurm.Check();
  const auto t0 = std::chrono::steady_clock::now();
  const std::string started_utc = UtcNow();
  const std::string sbatch = FindInPath("sbatch");
  const fs::path out = fs::absolute(base_options.out_dir).lexically_normal();
  const fs::path state = out / kStateDir;
  const fs::path slurm_dir = out / "slurm";
  std::error_code ec;
  fs::create_directories(state / "shards", ec);
  fs::create_directories(slurm_dir, ec);
  if (ec) throw Error(out.string(), "cannot create output folder: " + ec.message());

  BatchOptions options = base_options;
  options.out_dir = out.string();
  const std::string manifest = (state / "library.txt").string();
  FreezeLibrary(options.library, manifest);
  options.library = manifest;
  const BatchPlan plan = PlanInShards(&options, slurm.shards);
  const int shards = options.shard_count;
  WriteJsonAtomic((state / "plan.json").string(), PlanToJson(plan));
  ForgetEarlierSubmission(slurm_dir, state);
  const std::string job = (slurm_dir / "job.sh").string();
  WriteJobScript(job, options, slurm, manifest);
  const std::string job_id = SubmitJobArray(sbatch, options, slurm, slurm_dir, job);
  std::cerr << "batch: submitted Slurm job " << job_id << ": " << plan.films.size() << " films in "
            << shards << " array task(s); state in " << out.string() << "\n";
  if (!slurm.wait) {
    std::cerr << "batch: not waiting; follow with: hapcine batch --status "
              << ShellQuote(out.string()) << "\n";
    return 0;
  }
  if (!WaitForTasks(out.string(), job_id, shards, slurm, t0)) return 1;

  const int exit_code = TasksExitCode(out.string(), shards);
  BatchSummary merged = MergeShardSummaries(options, plan);
  merged.library = base_options.library;
  merged.started_utc = started_utc;
  merged.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WriteSummary(merged);
  PrintJobTotals(merged, job_id, out);
  return std::max(exit_code, merged.ExitCode());
}

}  // namespace hapcine::batch
