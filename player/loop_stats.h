#pragma once
// Statistics of the 1 kHz loop, gathered inside the tick without allocation:
// fixed 1-microsecond histograms (0..50 ms; larger values count in the top
// bin and in max).

#include <cstdint>
#include <string>
#include <vector>

namespace hapcine {

class MicroHistogram {
 public:
  MicroHistogram() : bins_(kBins, 0) {}
  void Add(double value_s) noexcept;
  // Quantile q in [0, 1], seconds (bin resolution: 1 us). 0 if empty.
  double Quantile(double q) const;
  double max_s() const { return max_s_; }
  double mean_s() const { return count_ ? sum_s_ / count_ : 0; }
  int64_t count() const { return count_; }

 private:
  static constexpr int kBins = 50001;
  std::vector<uint32_t> bins_;
  int64_t count_ = 0;
  double max_s_ = 0, sum_s_ = 0;
};

struct LoopStats {
  MicroHistogram period;      // time between tick starts
  MicroHistogram sync_error;  // |true media time - media time used|, when the clock knows the truth
  // |extrapolated - reported| media time at each update of a clock without
  // ground truth (mpv): the haptic-video sync error there.
  MicroHistogram extrapolation_error;
  MicroHistogram tick_work;            // time spent inside Tick (needs a time source)
  int64_t ticks = 0;
  int64_t missed_ticks = 0;  // periods skipped (a gap of 2.6 periods = 2 missed)
  int64_t seeks = 0;
  int watchdog_trips = 0;
  double first_tick_s = 0, last_tick_s = 0;
  double nominal_period_s = 0.001;

  // Multi-line human summary: ticks/s, period p50/p99/max, jitter, missed,
  // sync error.
  std::string Summary() const;
};

}  // namespace hapcine
