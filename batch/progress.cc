#include "batch/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hapcine::batch {

ProgressReporter::ProgressReporter(std::ostream& out, Mode mode, int total, int workers)
    : progress_(out, mode, "batch", "films"),
      mode_(mode),
      total_(total),
      workers_(workers < 1 ? 1 : workers),
      start_(std::chrono::steady_clock::now()) {
  if (mode_ == Mode::kBar) DrawBar();
}

double ProgressReporter::Eta(double mean_film_s, const std::vector<double>& running_elapsed,
                             int pending, int workers) {
  if (pending <= 0 && running_elapsed.empty()) return 0.0;
  if (mean_film_s < 0) return -1.0;
  double work = pending * mean_film_s;
  for (double e : running_elapsed) work += std::max(0.0, mean_film_s - e);
  return work / (workers < 1 ? 1 : workers);
}

double ProgressReporter::MeanFilmSeconds(int done, double done_seconds, int failed,
                                         double failed_seconds, int running) {
  if (done > 0) return done_seconds / done;
  if (failed > 0 && running == 0) return failed_seconds / failed;
  return -1.0;
}

void ProgressReporter::Started(const std::string& id) {
  std::lock_guard<std::mutex> lock(mu_);
  running_[id] = std::chrono::steady_clock::now();
}

void ProgressReporter::Finished(const std::string& id, const std::string& status, double seconds,
                                bool reused, const std::string& reason) {
  std::lock_guard<std::mutex> lock(mu_);
  running_.erase(id);
  ++finished_;
  if (status == "failed") {
    ++failed_;
    failed_seconds_ += seconds;
  } else if (!reused) {
    ++done_;
    done_seconds_ += seconds;
  }
  if (mode_ == Mode::kLines) {
    std::string line = "batch: [" + std::to_string(finished_) + "/" + std::to_string(total_) + "] " +
                       status + " " + id;
    if (!reused) line += " (" + FormatDuration(seconds) + ")";
    if (!reason.empty()) line += ": " + reason;
    progress_.Line(line);
  } else if (mode_ == Mode::kBar) {
    if (status == "failed") progress_.Line("failed " + id + ": " + reason);
    DrawBar();
  }
}

void ProgressReporter::DrawBar() {
  const auto now = std::chrono::steady_clock::now();
  std::vector<double> running_elapsed;
  for (const auto& [id, t0] : running_) {
    running_elapsed.push_back(std::chrono::duration<double>(now - t0).count());
  }
  const int running = static_cast<int>(running_.size());
  ProgressSnapshot s;
  s.done = finished_;
  s.total = total_;
  s.eta_s = Eta(MeanFilmSeconds(done_, done_seconds_, failed_, failed_seconds_, running),
                running_elapsed, total_ - finished_ - running, workers_);
  s.note = "elapsed " + FormatDuration(std::chrono::duration<double>(now - start_).count());
  if (failed_ > 0) s.note += " (" + std::to_string(failed_) + " failed)";
  progress_.Show(s);
}

void ProgressReporter::Tick() {
  std::lock_guard<std::mutex> lock(mu_);
  if (mode_ == Mode::kBar) DrawBar();
}

void ProgressReporter::Close() {
  std::lock_guard<std::mutex> lock(mu_);
  progress_.Close();
}

}  // namespace hapcine::batch
