#pragma once
// The safety layer between Equation 7 and the hardware, whatever the input:
// a haptic track with garbage, a controller bug, a stalled video, a signal.
//
// Per actuator (ActuatorSafety), every tick:
//   target: non-finite -> hold the last safe target (fault); clamp to the
//           workspace cube (+-workspace_half_m); rate-limit the step.
//   force:  non-finite -> zero at once (fault); clamp |F| to max_force_n;
//           rate-limit the change |dF| per tick; scale by the watchdog gain
//           (an output that grows is rate-limited again; one that shrinks
//           towards zero is not); a final clamp + finiteness check: whatever
//           went in, what comes out is finite and |F| <= max_force_n.
// Watchdog (one per loop): when the media clock stalls or the loop misses
// deadlines, the gain ramps linearly to zero within watchdog_ramp_s (20 ms);
// after recover_after_s of health it ramps back up over recover_ramp_s.
// Exit paths: ZeroForceGuard (RAII) zeroes and closes the seat in its
// destructor; SIGINT/SIGTERM set an atomic flag the loop polls each tick.
// Nothing here allocates or locks: safe in the 1 kHz tick.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>

#include "core/stop_signal.h"  // SIGINT/SIGTERM -> StopRequested(), polled by the loop
#include "haptics/device.h"

namespace hapcine {

struct SafetyOptions {
  double max_force_n = 9.0;           // |F| limit (min'd with the device's own)
  double workspace_half_m = 0.05;     // targets clamped to the 0.10 m cube
  double max_target_step_m = 0.0005;  // per tick: 0.5 m/s at 1 kHz
  double max_force_step_n = 0.5;      // per tick: 500 N/s at 1 kHz
  double watchdog_ramp_s = 0.02;      // force -> 0 within this after a trip
  double clock_stall_s = 0.25;        // no media-clock update this long while playing = stall
  double max_tick_gap_s = 0.005;      // a tick later than this = missed deadline
  double recover_after_s = 0.1;       // healthy this long before ramping back up
  double recover_ramp_s = 0.5;        // gain 0 -> 1 after recovery
  void Check() const;                 // throws UsageError
};

// Bits of ActuatorSafety::faults().
enum SafetyFault : uint32_t {
  kFaultNonFiniteTarget = 1u << 0,
  kFaultNonFiniteForce = 1u << 1,
  kFaultTargetClamped = 1u << 2,
  kFaultForceClamped = 1u << 3,
};

class ActuatorSafety {
 public:
  ActuatorSafety() = default;
  ActuatorSafety(const SafetyOptions& options, double device_max_force_n);

  // Returns the safe target for this tick.
  Eigen::Vector3d FilterTarget(const Eigen::Vector3d& target_m) noexcept;
  // Returns the safe force for this tick; `gain` in [0, 1] from the watchdog.
  Eigen::Vector3d FilterForce(const Eigen::Vector3d& force_n, double gain) noexcept;
  // Re-seeds the target filter (e.g. at the measured position on start).
  void ResetTarget(const Eigen::Vector3d& pos_m) noexcept;
  // Forgets the force history (after zero was sent by someone else).
  void ResetForce() noexcept {
    last_force_n_.setZero();
    last_out_n_.setZero();
  }

  double max_force_n() const { return max_force_n_; }
  uint32_t faults() const { return faults_; }            // sticky, OR of SafetyFault
  uint32_t tick_faults() const { return tick_faults_; }  // this tick only
  void ClearTickFaults() { tick_faults_ = 0; }

 private:
  SafetyOptions o_;
  double max_force_n_ = 0;
  Eigen::Vector3d last_target_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_force_n_ = Eigen::Vector3d::Zero();  // before the gain
  Eigen::Vector3d last_out_n_ = Eigen::Vector3d::Zero();    // as sent
  uint32_t faults_ = 0, tick_faults_ = 0;
};

class Watchdog {
 public:
  Watchdog() = default;
  explicit Watchdog(const SafetyOptions& options) : o_(options) {}
  // Once per tick: `dt_s` since the previous tick, `healthy` this tick.
  // Returns the force gain in [0, 1].
  double Update(double dt_s, bool healthy) noexcept;
  double gain() const { return gain_; }
  bool tripped() const { return tripped_; }
  int trips() const { return trips_; }

 private:
  SafetyOptions o_;
  double gain_ = 1;
  bool tripped_ = false;
  double healthy_for_s_ = 0;
  int trips_ = 0;
};

// Zero force and close on scope exit: every return, every exception.
class ZeroForceGuard {
 public:
  explicit ZeroForceGuard(HapSeat& seat) : seat_(seat) {}
  ~ZeroForceGuard() { ZeroAndClose(seat_); }
  ZeroForceGuard(const ZeroForceGuard&) = delete;
  ZeroForceGuard& operator=(const ZeroForceGuard&) = delete;

 private:
  HapSeat& seat_;
};


}  // namespace hapcine
