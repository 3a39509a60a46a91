#pragma once
// Progress of a batch on stderr, drawn by core/progress.h: a redrawn bar
// with counts and ETA on a terminal; plain lines (one per finished film)
// otherwise, so logs of Slurm tasks and CI stay readable.

#include <chrono>
#include <map>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "core/progress.h"

namespace hapcine::batch {

class ProgressReporter {
 public:
  using Mode = ProgressMode;
  // total: films to consider; workers: parallel jobs (for the ETA).
  ProgressReporter(std::ostream& out, Mode mode, int total, int workers);

  // A worker started on film `id` (its elapsed time feeds the ETA).
  void Started(const std::string& id);
  // A film finished with `status` ("done", "skipped", "failed", ...) after
  // `seconds` of work; `reused` = true if no work was needed (skipped,
  // duplicate), which must not count towards the ETA's time per film.
  void Finished(const std::string& id, const std::string& status, double seconds, bool reused,
                const std::string& reason);
  void Close();  // ends the bar's line
  void Tick();   // redraws the bar (elapsed time) if in bar mode

  // Estimated seconds left: the work still expected of the running films
  // (mean_film_s minus their elapsed time, at least 0) plus mean_film_s for
  // each pending film, shared by the workers. mean_film_s < 0 = not known
  // yet -> returns -1. Exposed for tests.
  static double Eta(double mean_film_s, const std::vector<double>& running_elapsed, int pending,
                    int workers);

  // Mean seconds per film for the ETA: of films processed to the end (done)
  // if any, since failures are often instant and would make a wildly short
  // ETA; else of failed films once nothing is running; else -1.
  static double MeanFilmSeconds(int done, double done_seconds, int failed, double failed_seconds,
                                int running);

 private:
  void DrawBar();
  std::mutex mu_;
  Progress progress_;
  Mode mode_;
  int total_;
  int workers_;
  int finished_ = 0;
  int failed_ = 0;
  int done_ = 0;
  double done_seconds_ = 0.0;
  double failed_seconds_ = 0.0;
  std::map<std::string, std::chrono::steady_clock::time_point> running_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hapcine::batch
