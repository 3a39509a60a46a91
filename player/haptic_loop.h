#pragma once
// The haptic loop of the player: one tick per millisecond, Equation 7 of the
// paper per actuator, through the safety layer, to the devices.
//
// Tick(now):
//   1. read the media clock, extrapolate to `now` (media time t);
//      detect seeks (seek serial or a jump > seek_jump_s) and end of film;
//   2. G'_A = track(t) (HapticTrack::Sample with a hint: allocation-free),
//      blended by a cosine ramp after a seek (seek_ramp_s), at start
//      (start_ramp_s, from where the grip is) and at the end of the film
//      (end_ramp_s, back to the centre); pause holds t, so holds G';
//   3. safety: target clamp + rate limit; F_A = k (G'_A - P_A) - d V_A
//      with P, V from the previous exchange; force clamp, rate limit,
//      watchdog gain (clock stall / missed deadlines -> 0 within 20 ms);
//   4. Exchange(F) with every device; a device fault stops the loop.
// Tick() is deterministic given `now` and the clock, so tests step it
// synchronously; LoopRunner (loop_runner.h) calls it from a 1 kHz thread.
// Inside Tick: no allocation, no locks, no I/O. The last 2048 ticks are kept
// in a ring buffer and written out (DumpRecent) after a fault.

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/haptic_track.h"
#include "haptics/device.h"
#include "haptics/safety.h"
#include "player/loop_stats.h"
#include "player/media_clock.h"

namespace hapcine {

struct LoopOptions {
  double rate_hz = 1000;      // tick rate
  double k_n_m = 300;         // spring constant k of Eq. 7, N/m
  double d_n_s_m = 2;         // damping constant d of Eq. 7, N s/m
  double seek_ramp_s = 0.3;   // cosine ramp to the new target after a seek
  double start_ramp_s = 1.0;  // from the grip's position to the track at start
  double end_ramp_s = 1.0;    // back to the centre at the end of the film
  double seek_jump_s = 0.25;  // a clock jump larger than this is a seek
  bool finish_at_end = true;  // Tick() returns false at the film's end, back at the centre
  bool stop_on_request = true;  // StopRequested() (SIGINT/SIGTERM) stops the loop
  SafetyOptions safety;
  void Check() const;  // throws UsageError
};

enum class LoopStatus { kRunning, kFinished, kStopped, kFaulted };

struct TickRecord {
  double wall_s = 0, media_s = 0;
  float target_m[kNumActuators][3] = {};
  float pos_m[kNumActuators][3] = {};
  float force_n[kNumActuators][3] = {};
  float gain = 0;
  uint32_t flags = 0;  // OR of safety tick faults
};

class HapticLoop {
 public:
  // `track`, `seat` and `clock` must outlive the loop.
  HapticLoop(const HapticTrack& track, HapSeat& seat, const MediaClock& clock, LoopOptions options);

  // One tick at wall time now_s (SteadySeconds()). Returns false once the
  // loop is done (finished, stopped by a signal, or faulted); zero force has
  // then been sent. An exception from a device: zero force everywhere,
  // status kFaulted, rethrown.
  bool Tick(double now_s);
  // Zero force to every device now (an exit path). Never throws.
  void ZeroAll() noexcept;

  // Optional: a time source read right after the exchange, so the sync error
  // includes the tick's own latency (the runner uses SteadySeconds).
  void set_time_source(double (*now_fn)()) { now_fn_ = now_fn; }

  LoopStatus status() const { return status_; }
  const std::string& fault_message() const { return fault_; }
  const LoopStats& stats() const { return stats_; }
  const Eigen::Vector3d& last_force_n(int a) const { return force_n_[a]; }
  const Eigen::Vector3d& last_target_m(int a) const { return target_m_[a]; }
  const DeviceState& last_state(int a) const { return state_[a]; }
  // Media time of the last tick; readable from another thread (progress).
  double last_media_s() const { return last_media_s_.load(std::memory_order_relaxed); }
  // Every device of the seat reported homed at the last tick; readable from
  // another thread (the player starts the film then).
  bool all_homed() const { return all_homed_.load(std::memory_order_relaxed); }
  double gain() const { return watchdog_.gain(); }
  // Writes the ring buffer (oldest first) as CSV. Not real-time safe.
  void DumpRecent(std::ostream& out) const;

 private:
  void StartRamp(int a, double now_s, double len_s);
  bool Fail(const char* why);
  // The steps of one tick, in order (Tick runs them).
  double RecordTiming(double now_s);                        // -> seconds since the last tick
  bool ReadClockSeek(ClockReading* reading);                // -> a seek happened
  void StartEndOrSeekRamps(const ClockReading& r, double t, bool seek, double now_s);
  TickRecord& NextRecord(double now_s, double media_s, double gain);
  Eigen::Vector3d RampedGoal(int a, const Eigen::Vector3d& track_m, double now_s);
  // Commands actuator `a` (Eq. 7 through the safety layer); false on a device fault.
  bool DriveActuator(int a, const Eigen::Vector3d& track_m, double now_s, double gain,
                     TickRecord* rec, bool* homed);
  void RecordSync(const ClockReading& r, double t, double now_s);

  const HapticTrack& track_;
  HapSeat& seat_;
  const MediaClock& clock_;
  LoopOptions o_;
  double (*now_fn_)() = nullptr;

  std::array<ActuatorSafety, kNumActuators> safety_;
  Watchdog watchdog_;
  LoopStats stats_;
  LoopStatus status_ = LoopStatus::kRunning;
  std::string fault_;

  std::array<Eigen::Vector3d, kNumActuators> target_m_, force_n_, ramp_from_m_;
  std::array<DeviceState, kNumActuators> state_;
  std::array<double, kNumActuators> ramp_start_s_{}, ramp_len_s_{};
  std::array<bool, kNumActuators> started_{};
  size_t hint_ = 0;
  bool have_last_tick_ = false;
  double last_tick_s_ = 0;
  std::atomic<double> last_media_s_{0};
  std::atomic<bool> all_homed_{false};
  ClockReading prev_reading_;
  bool ending_ = false;
  double end_start_s_ = 0;

  std::vector<TickRecord> ring_;
  size_t ring_next_ = 0;
  bool ring_wrapped_ = false;
};

}  // namespace hapcine
