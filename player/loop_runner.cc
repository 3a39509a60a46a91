#include "player/loop_runner.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

namespace hapcine {
namespace {

void AddNs(timespec* t, long ns) {
  t->tv_nsec += ns;
  while (t->tv_nsec >= 1000000000L) {
    t->tv_nsec -= 1000000000L;
    ++t->tv_sec;
  }
}

double ToSeconds(const timespec& t) {
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

RunReport RunLoop(HapticLoop& loop, const RunnerOptions& options, const std::atomic<bool>* cancel,
                  const std::function<void()>& progress, double progress_period_s) {
  RunReport report;
  std::atomic<bool> done{false};
  loop.set_time_source(&SteadySeconds);
  std::thread worker([&] {
    if (options.realtime) {
      sched_param param{};
      param.sched_priority = options.priority;
      const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
      report.realtime = rc == 0;
      if (rc != 0)
        report.realtime_note =
            std::string("SCHED_FIFO not permitted (") + std::strerror(rc) +
            "); running at normal priority. Grant rtprio (e.g. limits.conf) for less jitter.";
    } else {
      report.realtime_note = "real-time scheduling not requested";
    }
    const long ns = static_cast<long>(std::llround(loop.stats().nominal_period_s * 1e9));
    timespec next;
    clock_gettime(CLOCK_MONOTONIC, &next);
    const double start = ToSeconds(next);
    try {
      for (;;) {
        AddNs(&next, ns);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
        }
        const double now = SteadySeconds();
        if ((cancel && cancel->load(std::memory_order_relaxed)) ||
            (options.max_run_s > 0 && now - start >= options.max_run_s))
          break;
        if (!loop.Tick(now)) break;
        if (now - ToSeconds(next) > 10 * loop.stats().nominal_period_s)
          clock_gettime(CLOCK_MONOTONIC, &next);
      }
    } catch (...) {
      report.error = std::current_exception();
    }
    loop.ZeroAll();
    report.elapsed_s = SteadySeconds() - start;
    done.store(true);
  });
  if (progress) {
    while (!done.load()) {
      std::this_thread::sleep_for(std::chrono::duration<double>(progress_period_s));
      if (!done.load()) progress();
    }
  }
  worker.join();
  return report;
}

}  // namespace hapcine
