#pragma once
// Runs a HapticLoop on its own thread at a fixed period: absolute-time sleeps
// (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)) so errors do not
// accumulate, SCHED_FIFO when the system permits it (otherwise a quiet
// fallback to normal scheduling, reported in RunReport). If the thread falls
// more than 10 periods behind it re-anchors instead of bursting ticks (the
// loop counts the missed ticks and its watchdog ramps the force down).

#include <atomic>
#include <exception>
#include <functional>
#include <string>

#include "player/haptic_loop.h"

namespace hapcine {

struct RunnerOptions {
  bool realtime = true;  // try SCHED_FIFO
  int priority = 80;     // SCHED_FIFO priority (1..99)
  double max_run_s = 0;  // > 0: stop after this long (benchmarks, smoke tests)
};

struct RunReport {
  bool realtime = false;      // SCHED_FIFO granted
  std::string realtime_note;  // why not, if not
  double elapsed_s = 0;
  std::exception_ptr error;  // an exception from the tick (zero force was sent)
};

// Blocks until the loop finishes, `cancel` becomes true, or max_run_s
// passes. Zero force is sent on every way out. `progress` (optional) is
// called from the calling thread about every progress_period_s while the
// loop runs (never from the loop's thread).
RunReport RunLoop(HapticLoop& loop, const RunnerOptions& options,
                  const std::atomic<bool>* cancel = nullptr,
                  const std::function<void()>& progress = {}, double progress_period_s = 0.5);

}  // namespace hapcine
