#pragma once
// One progress bar over a film's steps (`hapcine make`), with an ETA.
//
// The steps are child processes writing their progress to their logs as
// lines ("estimate: 300/1000 frames, 24.1/s, ETA 29.0s", core/progress.h);
// Tick() reads the running step's last such line. Each step weighs what it
// typically costs (estimate ~1 per frame, a preview ~0.6, haptics and plots
// a few percent); a reused step weighs nothing. The ETA is the elapsed time
// times what is left over what is done.

#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "batch/film_runner.h"
#include "batch/make.h"
#include "core/progress.h"

namespace hapcine::batch {

// Relative cost of a step by name ("estimate", "haptics-cinematic", ...).
double StepWeight(const std::string& step);

// The last "<label>: D/T" progress line in the log's tail: true with the
// fraction D/T in [0, 1]; false when there is none.
bool LastStepFraction(const std::string& log_path, double* fraction);

// Share of the job done: finished weights plus the running step's share,
// over all weights; 0 when nothing weighs anything.
double JobFraction(const std::vector<double>& weights, int running, double running_fraction);

class JobProgress : public FilmObserver {
 public:
  // `steps`: the steps in run order (MakeStepNames).
  JobProgress(std::ostream& out, ProgressMode mode, const std::string& label,
              const std::vector<std::string>& steps);
  void StepStarted(const std::string& step, const std::string& log_path, bool reused) override;
  void Tick();   // redraws (call every ~0.2 s from another thread)
  void Close();  // ends the bar's line

 private:
  std::mutex mu_;
  Progress progress_;
  ProgressMode mode_;
  std::vector<std::string> steps_;
  std::vector<double> weights_;
  int running_ = -1;
  std::string log_path_;
  double last_line_s_ = -1e300;
  double start_s_ = 0;
};

// RunMake on a worker thread while this one redraws a bar labelled `label`
// over the film's steps on `out`; rethrows what RunMake threw. Shared by
// `hapcine make` and `hapcine studio`.
MakeResult RunMakeWithProgress(const MakeOptions& options, const FilmLayout& layout,
                               std::ostream& out, ProgressMode mode, const std::string& label);

}  // namespace hapcine::batch
