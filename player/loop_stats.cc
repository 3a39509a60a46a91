#include "player/loop_stats.h"

#include <cmath>
#include <cstdio>

namespace hapcine {

void MicroHistogram::Add(double value_s) noexcept {
  if (!std::isfinite(value_s)) return;
  const double v = value_s < 0 ? -value_s : value_s;
  long us = std::lround(v * 1e6);
  if (us >= kBins) us = kBins - 1;
  ++bins_[static_cast<size_t>(us)];
  ++count_;
  sum_s_ += v;
  if (v > max_s_) max_s_ = v;
}

double MicroHistogram::Quantile(double q) const {
  if (count_ == 0) return 0;
  const double target = q * static_cast<double>(count_);
  int64_t seen = 0;
  for (int i = 0; i < kBins; ++i) {
    seen += bins_[i];
    if (static_cast<double>(seen) >= target && seen > 0) return i * 1e-6;
  }
  return max_s_;
}

std::string LoopStats::Summary() const {
  char buf[1024];
  const double span = last_tick_s - first_tick_s;
  const double tps = span > 0 ? (ticks - 1) / span : 0;
  const double p50 = period.Quantile(0.5), p99 = period.Quantile(0.99);
  int n = std::snprintf(
      buf, sizeof(buf),
      "haptic loop: %lld ticks in %.3f s = %.1f ticks/s (nominal %.0f)\n"
      "  period p50 %.1f us, p99 %.1f us, max %.1f us; jitter p99 |p99 - nominal| %.1f us\n"
      "  missed ticks (gap > 1.5 periods; a gap of n periods counts n - 1) %lld, watchdog trips %d, seeks %lld\n",
      static_cast<long long>(ticks), span, tps, 1.0 / nominal_period_s, p50 * 1e6, p99 * 1e6,
      period.max_s() * 1e6, std::abs(p99 - nominal_period_s) * 1e6,
      static_cast<long long>(missed_ticks), watchdog_trips, static_cast<long long>(seeks));
  std::string s(buf, n);
  if (sync_error.count() > 0) {
    n = std::snprintf(
        buf, sizeof(buf),
        "  sync error (true media clock - time used) p50 %.1f us, p99 %.1f us, max %.1f us\n",
        sync_error.Quantile(0.5) * 1e6, sync_error.Quantile(0.99) * 1e6, sync_error.max_s() * 1e6);
    s.append(buf, n);
  }
  if (extrapolation_error.count() > 0) {
    n = std::snprintf(
        buf, sizeof(buf),
        "  haptic-video sync error at player clock updates (%lld; |haptic time - video time|) p50 "
        "%.2f ms, p99 %.2f ms, max %.2f ms\n",
        static_cast<long long>(extrapolation_error.count()),
        extrapolation_error.Quantile(0.5) * 1e3, extrapolation_error.Quantile(0.99) * 1e3,
        extrapolation_error.max_s() * 1e3);
    s.append(buf, n);
  }
  if (tick_work.count() > 0) {
    n = std::snprintf(buf, sizeof(buf), "  tick work p50 %.1f us, p99 %.1f us, max %.1f us\n",
                      tick_work.Quantile(0.5) * 1e6, tick_work.Quantile(0.99) * 1e6,
                      tick_work.max_s() * 1e6);
    s.append(buf, n);
  }
  return s;
}

}  // namespace hapcine
