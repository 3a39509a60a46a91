#include "batch/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hapcine::batch {

std::string FormatDuration(double seconds) {
  char buf[32];
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  if (seconds < 60) {
    std::snprintf(buf, sizeof(buf), "%.1fs", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds + 0.5);
    std::snprintf(buf, sizeof(buf), "%dm%02ds", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60 + 0.5);
    std::snprintf(buf, sizeof(buf), "%dh%02dm", m / 60, m % 60);
  }
  return buf;
}

ProgressReporter::ProgressReporter(std::ostream& out, Mode mode, int total, int workers)
    : out_(out),
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
    out_ << "batch: [" << finished_ << "/" << total_ << "] " << status << " " << id;
    if (!reused) out_ << " (" << FormatDuration(seconds) << ")";
    if (!reason.empty()) out_ << ": " << reason;
    out_ << "\n" << std::flush;
  } else if (mode_ == Mode::kBar) {
    if (status == "failed") {
      out_ << "\r\033[K"
           << "failed " << id << ": " << reason << "\n";
    }
    DrawBar();
  }
}

void ProgressReporter::DrawBar() {
  constexpr int kWidth = 30;
  const int filled = total_ > 0 ? finished_ * kWidth / total_ : kWidth;
  std::string bar(filled, '#');
  bar += std::string(kWidth - filled, '.');
  const auto now = std::chrono::steady_clock::now();
  std::vector<double> running_elapsed;
  for (const auto& [id, t0] : running_) {
    running_elapsed.push_back(std::chrono::duration<double>(now - t0).count());
  }
  const int running = static_cast<int>(running_.size());
  const double eta = Eta(MeanFilmSeconds(done_, done_seconds_, failed_, failed_seconds_, running),
                         running_elapsed, total_ - finished_ - running, workers_);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  out_ << "\r\033[K[" << bar << "] " << finished_ << "/" << total_;
  if (failed_ > 0) out_ << " (" << failed_ << " failed)";
  out_ << "  elapsed " << FormatDuration(elapsed) << "  ETA "
       << (eta < 0 ? "?" : FormatDuration(eta)) << std::flush;
}

void ProgressReporter::Tick() {
  std::lock_guard<std::mutex> lock(mu_);
  if (mode_ == Mode::kBar) DrawBar();
}

void ProgressReporter::Close() {
  std::lock_guard<std::mutex> lock(mu_);
  if (mode_ == Mode::kBar) out_ << "\n" << std::flush;
}

}  // namespace hapcine::batch
