#pragma once
// Diagnostic: `HAPCINE_TIMING=1 hapcine estimate ...` prints one line per
// stage to stderr: wall seconds since the first stage logged, and the CPU
// seconds of the calling thread. Used to see which stage of the estimation
// thread is on the critical path after tracking ends (docs/estimate.md "Speed").

#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace hapcine {

inline void LogStage(const char* what, int detail = -1) {
  static const bool enabled = std::getenv("HAPCINE_TIMING") != nullptr;
  if (!enabled) return;
  static const auto start = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  timespec cpu{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
  std::fprintf(stderr, "timing %8.3f s wall  %7.3f s thread CPU  %s", wall,
               cpu.tv_sec + 1e-9 * cpu.tv_nsec, what);
  if (detail >= 0) std::fprintf(stderr, " %d", detail);
  std::fprintf(stderr, "\n");
}

}  // namespace hapcine
