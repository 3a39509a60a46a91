#pragma once
// Progress of a batch on stderr: a redrawn bar with counts and ETA on a
// terminal; plain lines (one per finished film) otherwise, so logs of Slurm
// tasks and CI stay readable.

#include <chrono>
#include <mutex>
#include <ostream>
#include <string>

namespace hapcine::batch {

class ProgressReporter {
 public:
  enum class Mode { kBar, kLines, kQuiet };
  // total: films to consider; workers: parallel jobs (for the ETA).
  ProgressReporter(std::ostream& out, Mode mode, int total, int workers);

  // A film finished with `status` ("done", "skipped", "failed", ...) after
  // `seconds` of work; `reused` = true if no work was needed (skipped,
  // duplicate), which must not count towards the ETA's time per film.
  void Finished(const std::string& id, const std::string& status, double seconds, bool reused,
                const std::string& reason);
  void Close();  // ends the bar's line
  void Tick();   // redraws the bar (elapsed time) if in bar mode

  // Estimated seconds left: mean time of worked films x films left / workers
  // (negative if not known yet). Exposed for tests.
  static double Eta(int worked, double worked_seconds, int left, int workers);

 private:
  void DrawBar();
  std::mutex mu_;
  std::ostream& out_;
  Mode mode_;
  int total_;
  int workers_;
  int finished_ = 0;
  int failed_ = 0;
  int worked_ = 0;
  double worked_seconds_ = 0.0;
  std::chrono::steady_clock::time_point start_;
};

std::string FormatDuration(double seconds);  // "1h02m", "3m12s", "4.2s"

}  // namespace hapcine::batch
