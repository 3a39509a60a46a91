#pragma once
// Beyond one machine: the library as a Slurm job array.
//
// SubmitSlurmBatch freezes the library into OUT_DIR/.batch/library.txt (a
// manifest of absolute paths, so every task sees the same films in the same
// order), writes OUT_DIR/.batch/plan.json and OUT_DIR/slurm/job.sh, and runs
//   sbatch --parsable --array=0-(K-1) --output=OUT_DIR/slurm/task-%a.log ... job.sh
// Task i runs `hapcine batch library.txt -o OUT_DIR --shard i/K ...`: the same
// resumable per-film state as a local run (a film is only ever processed by
// the task that owns it; the film locks guard against a concurrent local run),
// then writes OUT_DIR/slurm/task-i.status ("<exit code> <job id>") atomically.
//
// Waiting does not use `sbatch --wait` (it polls after 2 s, 8 s, then every
// 32 s): the submitter polls the status files every poll_s and asks squeue
// every few seconds whether the job is still there, so a task that died
// without writing its status (node failure, scancel) is noticed too. Then it
// merges the tasks' summaries into OUT_DIR/summary.json and summary.txt.

#include <string>
#include <vector>

#include "batch/batch.h"
#include "batch/batch_options.h"

namespace hapcine::batch {

struct SlurmOptions {
  // Array tasks (shards); capped at the number of films to process.
  int shards = 4;
  // Wait for the array to finish and write the merged summary.
  bool wait = true;
  // Extra sbatch words, e.g. {"--partition=gpu", "--time=02:00:00"}.
  std::vector<std::string> sbatch_args;
  // The program each task runs as `<batch_exe> batch ...`; empty = this one.
  std::string batch_exe;
  // Seconds between looks at the status files while waiting.
  double poll_s = 1.0;
  // Give up waiting after this many seconds (0 = never); tasks keep running.
  double wait_timeout_s = 0.0;
  void Check() const;  // throws UsageError
};

// Quotes a word for a POSIX shell: 'it'\''s'.
std::string ShellQuote(const std::string& word);

// The body of job.sh (exposed for tests).
std::string SlurmJobScript(const BatchOptions& options, const SlurmOptions& slurm,
                           const std::string& manifest, int shards);

// Submits (and by default waits). Returns the exit code for the CLI: 0 if
// every task exited 0 and no film failed, 1 otherwise. Throws hapcine::Error
// if sbatch is missing or refuses the job.
int SubmitSlurmBatch(const BatchOptions& options, const SlurmOptions& slurm);

// Merges OUT_DIR/.batch/shards/summary-*-of-K.json; films of shards without
// a summary are reported failed with the reason. Used after waiting.
BatchSummary MergeShardSummaries(const BatchOptions& options, const BatchPlan& plan);

}  // namespace hapcine::batch
