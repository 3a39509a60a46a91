// Benchmark of the real 1 kHz haptic thread: plays a synthetic track on
// three simulated Falcons against the wall clock for ~10 s and prints ticks
// per second (target >= 995), period p50/p99/max and jitter (target: p99
// within 200 us of 1 ms), missed ticks and the sync error (true media clock
// at the moment the forces were sent minus the media time the forces were
// computed for).
//
//   build-<you>/player/hapcine_loop_bench [seconds] [--no-realtime]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "haptics/sim_device.h"
#include "player/loop_runner.h"

int main(int argc, char** argv) {
  using namespace hapcine;
  double seconds = 10;
  bool realtime = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--no-realtime") == 0) {
      realtime = false;
    } else if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf("usage: %s [seconds=10] [--no-realtime]\n", argv[0]);
      return 0;
    } else {
      seconds = std::atof(argv[i]);
      if (!(seconds > 0.5 && seconds < 3600)) {
        std::fprintf(stderr, "seconds must be in (0.5, 3600)\n");
        return 2;
      }
    }
  }
  HapticTrack track;
  track.rate_hz = 100;
  for (int i = 0; i <= static_cast<int>((seconds + 1) * 100); ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    for (int a = 0; a < kNumActuators; ++a)
      s.pos_m[a] = 0.02 * Eigen::Vector3d(std::sin(s.time_s * (1 + a)), std::cos(s.time_s * 0.7),
                                          std::sin(s.time_s * 0.3 * a));
    track.samples.push_back(s);
  }
  HapSeat seat;
  for (auto& d : seat.devices) {
    d = std::make_unique<SimDevice>();
    d->Open();
  }
  WallClock clock(track.samples.back().time_s);
  LoopOptions lo;
  lo.finish_at_end = true;
  HapticLoop loop(track, seat, clock, lo);
  RunnerOptions ro;
  ro.realtime = realtime;
  ro.max_run_s = seconds;
  std::printf("running the 1 kHz loop on 3 simulated Falcons for %.1f s...\n", seconds);
  const RunReport r = RunLoop(loop, ro);
  if (r.error) {
    std::fprintf(stderr, "the loop threw\n");
    return 1;
  }
  std::printf("scheduling: %s\n", r.realtime ? "SCHED_FIFO" : r.realtime_note.c_str());
  std::printf("%s", loop.stats().Summary().c_str());
  const LoopStats& s = loop.stats();
  const double tps = (s.ticks - 1) / (s.last_tick_s - s.first_tick_s);
  const double jitter_p99 = std::abs(s.period.Quantile(0.99) - s.nominal_period_s);
  std::printf("targets: ticks/s >= 995: %s (%.1f); period jitter p99 < 200 us: %s (%.1f us)\n",
              tps >= 995 ? "met" : "NOT met", tps, jitter_p99 < 200e-6 ? "met" : "NOT met",
              jitter_p99 * 1e6);
  return 0;
}
