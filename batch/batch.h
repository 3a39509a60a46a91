#pragma once
// `hapcine batch`: runs a whole library through estimate + haptics, resumably.
//
//   BatchOptions opt;  opt.library = "films/";  opt.out_dir = "out/";
//   BatchSummary s = RunLocalBatch(opt);     // N workers, one film each
//   int code = s.ExitCode();                  // 0 if nothing failed
//
// Every film's steps run as child processes (film_runner.h); state lives in
// files (state_files.h), so a run killed at any moment is resumed by running
// the same command again.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/batch_options.h"
#include "batch/film_runner.h"
#include "batch/plan.h"

namespace hapcine::batch {

struct BatchSummary {
  std::string library;
  std::string out_dir;
  std::string settings_hash;
  int shard_index = 0;
  int shard_count = 1;
  int jobs = 1;
  double wall_seconds = 0.0;
  std::string started_utc;
  std::vector<FilmOutcome> films;  // in plan order

  int Count(FilmStatus s) const;
  // 0 if every film is done, skipped or a duplicate; 1 otherwise.
  int ExitCode() const;
  nlohmann::json ToJson() const;
  static BatchSummary FromJson(const nlohmann::json& j);
  std::string ToText() const;  // human-readable, one line per film
};

// Runs the films of options' shard with options.ResolvedJobs() workers.
// Writes OUT_DIR/summary.json + summary.txt (unsharded), or
// OUT_DIR/.batch/shards/summary-<i>-of-<K>.json (sharded). Throws
// hapcine::Error for a missing library or an unwritable OUT_DIR.
BatchSummary RunLocalBatch(const BatchOptions& options);

// Writes summary.json and summary.txt into summary.out_dir.
void WriteSummary(const BatchSummary& summary);

// Progress of a batch from its state files alone (works while it runs,
// across Slurm tasks, after a crash).
struct BatchStatus {
  int total = 0, done = 0, failed = 0, duplicate = 0, running = 0, pending = 0;
  std::vector<std::pair<std::string, std::string>> failures;  // id, reason
  std::vector<std::string> slurm_tasks;                       // "task 0: exit 0", ... if any
  std::string ToText() const;
};
// Throws hapcine::Error if OUT_DIR holds no batch (.batch/plan.json).
BatchStatus ReadBatchStatus(const std::string& out_dir);

}  // namespace hapcine::batch
