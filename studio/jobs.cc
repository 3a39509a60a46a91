#include "studio/jobs.h"

#include <algorithm>

#include "core/error_message.h"

namespace hapcine::studio {

nlohmann::json JobStatus::ToJson() const {
  nlohmann::json j;
  j["state"] = state == JobState::kRunning ? "running" : state == JobState::kDone ? "done" : "failed";
  j["progress"] = progress;
  j["eta_s"] = eta_s ? nlohmann::json(*eta_s) : nlohmann::json(nullptr);
  j["path"] = path;
  j["error"] = error;
  return j;
}

JobRegistry::~JobRegistry() {
  std::map<std::string, std::unique_ptr<Job>> jobs;
  {
    std::lock_guard<std::mutex> lock(mu_);
    jobs.swap(jobs_);
  }
  for (auto& [id, job] : jobs) {
    if (job->thread.joinable()) job->thread.join();
  }
}

std::string JobRegistry::Start(JobWork work) {
  std::lock_guard<std::mutex> lock(mu_);
  return StartLocked(std::move(work));
}

std::string JobRegistry::StartOnce(const std::string& key, JobWork work) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = by_key_.find(key);
  if (it != by_key_.end()) {
    const auto job = jobs_.find(it->second);
    if (job != jobs_.end() && job->second->status.state != JobState::kFailed) return it->second;
  }
  const std::string id = StartLocked(std::move(work));
  by_key_[key] = id;
  return id;
}

std::string JobRegistry::StartLocked(JobWork work) {
  const std::string id = "j" + std::to_string(next_id_++);
  auto job = std::make_unique<Job>();
  job->started = std::chrono::steady_clock::now();
  Job* raw = job.get();
  jobs_[id] = std::move(job);
  raw->thread = std::thread([this, id, raw, work = std::move(work)] {
    const JobProgressFn progress = [this, raw](double p) {
      std::lock_guard<std::mutex> lock(mu_);
      raw->status.progress = std::clamp(p, 0.0, 1.0);
    };
    try {
      Finish(id, work(progress), "");
    } catch (...) {
      Finish(id, "", EscapedExceptionMessage(std::current_exception()));
    }
  });
  return id;
}

void JobRegistry::Finish(const std::string& id, const std::string& path, const std::string& error) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return;
  JobStatus& s = it->second->status;
  s.state = error.empty() ? JobState::kDone : JobState::kFailed;
  if (error.empty()) s.progress = 1.0;
  s.path = path;
  s.error = error;
}

std::optional<JobStatus> JobRegistry::Status(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  JobStatus s = it->second->status;
  if (s.state == JobState::kRunning && s.progress > 0.001) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second->started).count();
    s.eta_s = elapsed * (1.0 - s.progress) / s.progress;
  }
  return s;
}

}  // namespace hapcine::studio
