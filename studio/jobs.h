#pragma once
// Background work of the studio (a preview export, an H.264 proxy): each job
// runs on its own thread, reports its progress in [0, 1], and is asked about
// through GET /api/jobs/<id> (state, progress, an ETA from the elapsed time).

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

namespace hapcine::studio {

enum class JobState { kRunning, kDone, kFailed };

struct JobStatus {
  JobState state = JobState::kRunning;
  double progress = 0;            // [0, 1]
  std::optional<double> eta_s;    // while running, once progress > 0
  std::string path;               // done: the written file
  std::string error;              // failed: one line
  nlohmann::json ToJson() const;  // {"state","progress","eta_s","path","error"}
};

// Reports progress in [0, 1]; callable from the job's thread.
using JobProgressFn = std::function<void(double)>;
// The job's work: returns the path it wrote; throws on failure.
using JobWork = std::function<std::string(const JobProgressFn&)>;

class JobRegistry {
 public:
  JobRegistry() = default;
  ~JobRegistry();  // waits for running jobs
  JobRegistry(const JobRegistry&) = delete;
  JobRegistry& operator=(const JobRegistry&) = delete;

  // Starts `work` under a new id ("j1", "j2", ...).
  std::string Start(JobWork work);
  // Starts `work` under `key` unless a job of that key is running or done
  // (a proxy is made once); returns the job's id either way.
  std::string StartOnce(const std::string& key, JobWork work);
  std::optional<JobStatus> Status(const std::string& id) const;

 private:
  struct Job {
    JobStatus status;
    std::chrono::steady_clock::time_point started;
    std::thread thread;
  };
  std::string StartLocked(JobWork work);
  void Finish(const std::string& id, const std::string& path, const std::string& error);

  mutable std::mutex mu_;
  std::map<std::string, std::unique_ptr<Job>> jobs_;
  std::map<std::string, std::string> by_key_;
  int next_id_ = 1;
};

}  // namespace hapcine::studio
