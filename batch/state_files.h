#pragma once
// The on-disk state of a batch. Everything a re-run, a Slurm shard or
// `--status` needs is in files, each written atomically (temp + rename):
//
//   OUT_DIR/
//     <id>/                      one folder per film (library.h: FilmId)
//       <stem>.camera.csv        outputs, each renamed in when its step succeeded
//       <stem>.<model>.haptic.csv
//       <stem>.<model>.hjif
//       done.json                written LAST: input hash, settings, outputs, timings
//       failed.json              the failing step and its one-line reason
//       duplicate.json           this input has the same bytes as another film
//       .steps/<step>.json       stamp of a finished step (lets a re-run skip it)
//       logs/<step>.log          the step's stdout+stderr
//       .tmp/                    where running steps write; removed by every run
//       .lock                    flock()ed while a process works on the film
//     .batch/plan.json           the films, their hashes, duplicates and shards
//     .batch/library.txt         frozen manifest submitted to Slurm
//     .batch/shards/summary-<i>-of-<K>.json  each Slurm task's summary
//     slurm/job.sh, slurm/task-<i>.log, slurm/task-<i>.status
//     summary.json, summary.txt  the last run's summary

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace hapcine::batch {

constexpr const char* kDoneFile = "done.json";
constexpr const char* kFailedFile = "failed.json";
constexpr const char* kDuplicateFile = "duplicate.json";
constexpr const char* kLockFile = ".lock";
constexpr const char* kTempDir = ".tmp";
constexpr const char* kStepsDir = ".steps";
constexpr const char* kLogsDir = "logs";
constexpr const char* kStateDir = ".batch";

// Writes `j` (pretty) to path via a temporary file and rename.
void WriteJsonAtomic(const std::string& path, const nlohmann::json& j);
// The parsed file, or nullopt if missing or not valid JSON (a torn file can
// not exist thanks to the rename, but a user may have edited one).
std::optional<nlohmann::json> ReadJsonFile(const std::string& path);

// An exclusive, non-blocking flock() on <film dir>/.lock, released on
// destruction or when the process dies (even by SIGKILL).
class FilmLock {
 public:
  explicit FilmLock(const std::string& film_dir);
  ~FilmLock();
  FilmLock(const FilmLock&) = delete;
  FilmLock& operator=(const FilmLock&) = delete;
  bool locked() const { return fd_ >= 0 && locked_; }

 private:
  int fd_ = -1;
  bool locked_ = false;
};

// True if another process holds the film's lock right now.
bool FilmIsLocked(const std::string& film_dir);

// Removes what an interrupted run left: <dir>/.tmp/ and the output
// temporaries (core/output_files.h; also "*.tmp-<pid>" of earlier versions)
// in <dir> and <dir>/.steps. Call only while holding the film's lock.
// Returns the number of entries removed.
int CleanFilmTemp(const std::string& film_dir);

// Removes output temporaries (and "*.tmp-<pid>" files) directly in `dir`
// whose writer pid is not alive on this host (safe while other batches run).
int CleanDeadTempFiles(const std::string& dir);

// OUT_DIR/.batch/shards/summary-<shard>-of-<shards>.json: where shard
// `shard` of a sharded run writes its summary (the Slurm submitter merges them).
std::string ShardSummaryPath(const std::string& out_dir, int shard, int shards);

// UTC time as "2026-11-22T07:30:00Z".
std::string UtcNow();

}  // namespace hapcine::batch
