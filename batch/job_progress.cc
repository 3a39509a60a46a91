#include "batch/job_progress.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <thread>
#include <cstdlib>
#include <fstream>

namespace hapcine::batch {
namespace {

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// "label: D/T ..." -> D/T; false for any other line.
bool ParseProgressLine(const std::string& line, double* fraction) {
  const size_t colon = line.find(": ");
  if (colon == std::string::npos || line.rfind("hapcine ", 0) == 0) return false;
  const char* p = line.c_str() + colon + 2;
  char* end = nullptr;
  const double done = std::strtod(p, &end);
  if (end == p || *end != '/') return false;
  p = end + 1;
  const double total = std::strtod(p, &end);
  if (end == p || !(total > 0) || !(done >= 0)) return false;
  *fraction = std::clamp(done / total, 0.0, 1.0);
  return true;
}

}  // namespace

double StepWeight(const std::string& step) {
  if (step == "estimate") return 1.0;
  if (step == "preview") return 0.6;  // decode, draw, encode: about a decode and a half
  return 0.03;                        // haptics, plots: seconds against minutes
}

bool LastStepFraction(const std::string& log_path, double* fraction) {
  std::ifstream in(log_path, std::ios::binary);
  if (!in) return false;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(size > 8192 ? size - 8192 : 0);
  std::string line;
  bool found = false;
  while (std::getline(in, line)) {
    double f;
    if (ParseProgressLine(line, &f)) {
      *fraction = f;
      found = true;
    }
  }
  return found;
}

double JobFraction(const std::vector<double>& weights, int running, double running_fraction) {
  double total = 0, done = 0;
  for (size_t i = 0; i < weights.size(); ++i) {
    total += weights[i];
    if (static_cast<int>(i) < running) done += weights[i];
  }
  if (running >= 0 && running < static_cast<int>(weights.size())) {
    done += weights[running] * std::clamp(running_fraction, 0.0, 1.0);
  }
  return total > 0 ? done / total : 0.0;
}

JobProgress::JobProgress(std::ostream& out, ProgressMode mode, const std::string& label,
                         const std::vector<std::string>& steps)
    : progress_(out, mode, label, "%"), mode_(mode), steps_(steps), start_s_(NowSeconds()) {
  for (const std::string& s : steps_) weights_.push_back(StepWeight(s));
}

void JobProgress::StepStarted(const std::string& step, const std::string& log_path, bool reused) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = std::find(steps_.begin(), steps_.end(), step);
  if (it == steps_.end()) return;
  running_ = static_cast<int>(it - steps_.begin());
  // Reused work takes no time: it must not make the ETA optimistic.
  if (reused) weights_[running_] = 0;
  log_path_ = reused ? "" : log_path;
  if (mode_ != ProgressMode::kQuiet) {
    progress_.Line("make: " + step + (reused ? ": reused (film and settings unchanged)" : ""));
  }
}

void JobProgress::Tick() {
  std::lock_guard<std::mutex> lock(mu_);
  if (mode_ == ProgressMode::kQuiet || running_ < 0) return;
  const double now = NowSeconds();
  // Lines (a log, a pipe): one every 5 s, as every command's progress.
  if (mode_ == ProgressMode::kLines && now - last_line_s_ < 5.0) return;
  last_line_s_ = now;
  double step_fraction = 0;
  if (!log_path_.empty()) LastStepFraction(log_path_, &step_fraction);
  const double f = JobFraction(weights_, running_, step_fraction);
  if (mode_ == ProgressMode::kLines && f <= 0) return;  // nothing to say yet
  ProgressSnapshot s;
  s.done = static_cast<int>(f * 100);
  s.total = 100;
  s.note = steps_[running_];
  const double elapsed = now - start_s_;
  s.eta_s = f > 0.01 ? elapsed * (1 - f) / f : -1;
  progress_.Show(s);
}

void JobProgress::Close() {
  std::lock_guard<std::mutex> lock(mu_);
  progress_.Close();
}

MakeResult RunMakeWithProgress(const MakeOptions& options, const FilmLayout& layout,
                               std::ostream& out, ProgressMode mode, const std::string& label) {
  JobProgress progress(out, mode, label, MakeStepNames(layout));
  // The steps write a progress line every half second into their logs.
  ::setenv("HAPCINE_PROGRESS_INTERVAL", "0.5", 1);
  MakeResult result;
  std::exception_ptr failure;
  bool finished = false;
  std::mutex mu;
  std::condition_variable cv;
  std::thread worker([&] {
    try {
      result = RunMake(options, &progress);
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mu);
    finished = true;
    cv.notify_all();
  });
  {
    std::unique_lock<std::mutex> lock(mu);
    while (!cv.wait_for(lock, std::chrono::milliseconds(200), [&] { return finished; }))
      progress.Tick();
  }
  worker.join();
  progress.Close();
  if (failure) std::rethrow_exception(failure);
  return result;
}

}  // namespace hapcine::batch
