#include "player/simulate_seat.h"

#include <cmath>

#include "core/error.h"
#include "player/media_clock.h"

namespace hapcine {

HapticTrack SimulateSeat(const HapticTrack& track, const LoopOptions& loop_options,
                         const SimDeviceOptions& sim, double record_hz) {
  if (track.samples.empty()) throw Error(track.source, "haptic track has no rows");
  if (!(record_hz > 0 && record_hz <= loop_options.rate_hz))
    throw UsageError("record_hz must be in (0, loop rate]");
  HapSeat seat;
  std::array<SimDevice*, kNumActuators> sims{};
  for (int a = 0; a < kNumActuators; ++a) {
    auto d = std::make_unique<SimDevice>(sim);
    d->Open();
    sims[a] = d.get();
    seat.devices[a] = std::move(d);
  }
  // The clock a player would give: media time = the tick's time, eof at
  // the end of the track.
  FakeClock clock;
  LoopOptions lo = loop_options;
  lo.finish_at_end = true;
  lo.stop_on_request = false;  // offline, no device: a stale stop flag must not cut it short
  HapticLoop loop(track, seat, clock, lo);

  HapticTrack out;
  out.rate_hz = record_hz;
  out.model = track.model;
  out.source = track.source;
  out.metadata["response_of"] = "simulated seat (sim device, k=" + std::to_string(lo.k_n_m) +
                                ", d=" + std::to_string(lo.d_n_s_m) + ")";
  const double dt = 1.0 / lo.rate_hz;
  const double end_s = track.samples.back().time_s;
  const int every = std::max(1, static_cast<int>(std::lround(lo.rate_hz / record_hz)));
  // Ticks are counted in integers so the times are exact multiples of dt.
  const int64_t max_ticks =
      static_cast<int64_t>(std::ceil((end_s + lo.end_ramp_s + 1.0) * lo.rate_hz));
  for (int64_t i = 0; i < max_ticks; ++i) {
    const double t = static_cast<double>(i) * dt;
    clock.Update(std::min(t, end_s), t);
    if (t >= end_s && !clock.Read().eof) clock.SetEof(t);
    const bool running = loop.Tick(t);
    if (i % every == 0) {
      HapticSample s;
      s.time_s = t;
      for (int a = 0; a < kNumActuators; ++a) s.pos_m[a] = sims[a]->true_pos_m();
      out.samples.push_back(s);
    }
    if (!running) break;
  }
  if (loop.status() == LoopStatus::kFaulted)
    throw Error(track.source, "simulated seat faulted: " + loop.fault_message());
  return out;
}

}  // namespace hapcine
