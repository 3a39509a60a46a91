#pragma once
// Progress of a long-running command on stderr, one look for all of them:
// on a terminal a bar redrawn in place with the count, the rate and the ETA;
// otherwise (logs, CI, Slurm tasks) a plain line every few seconds, so a log
// stays readable. Quiet prints nothing.
//
//   bar:    estimate [#########.....................] 300/1000 frames  24.1/s  ETA 29.0s
//   lines:  estimate: 300/1000 frames, 24.1/s, ETA 29.0s
//   finish: estimate: 1000 frames in 41.5s (24.1/s)

#include <functional>
#include <ostream>
#include <string>

namespace hapcine {

// "4.2s", "3m12s", "1h02m"; "?" when negative or not finite.
std::string FormatDuration(double seconds);

enum class ProgressMode { kBar, kLines, kQuiet };

// kQuiet when `quiet`, else kBar when stderr is a terminal, else kLines.
ProgressMode ProgressModeFor(bool quiet);

// What one redraw shows. total <= 0: unknown (no bar, no ETA); eta_s < 0:
// unknown; note: free text after the count ("24.1/s", "2 failed").
struct ProgressSnapshot {
  double done = 0;
  double total = 0;
  double eta_s = -1;
  std::string note;
};

class Progress {
 public:
  // Seconds on a monotonic clock; the default is std::chrono::steady_clock.
  using Clock = std::function<double()>;

  // label: the command ("estimate"); unit: what is counted ("frames").
  Progress(std::ostream& out, ProgressMode mode, std::string label, std::string unit,
           Clock clock = {});

  // `done` of `total` (total <= 0: unknown): rate and ETA from the time since
  // construction. Throttled: a bar at most every 0.2 s, a line every 5 s.
  void Update(double done, double total);
  // Draws `snapshot` now (callers that estimate their own ETA).
  void Show(const ProgressSnapshot& snapshot);
  // A line of its own (a failure, a warning): above the bar on a terminal.
  void Line(const std::string& text);
  // Ends the bar and prints "<label>: <done> <unit> in <time> (<rate>/s)".
  void Finish(double done);
  // Ends the bar's line without a summary.
  void Close();

  // The text of one redraw, without the leading "\r\033[K" of a bar.
  static std::string BarText(const std::string& label, const std::string& unit,
                             const ProgressSnapshot& s);
  static std::string LineText(const std::string& label, const std::string& unit,
                              const ProgressSnapshot& s);

 private:
  double Now() const;
  std::ostream& out_;
  ProgressMode mode_;
  std::string label_, unit_;
  Clock clock_;
  double start_ = 0;
  double last_draw_ = -1e300;
  bool bar_open_ = false;
};

}  // namespace hapcine
