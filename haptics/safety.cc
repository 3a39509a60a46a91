#include "haptics/safety.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace hapcine {

void SafetyOptions::Check() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw UsageError(std::string("safety ") + name + " must be > 0");
  };
  positive(max_force_n, "max_force_n");
  positive(workspace_half_m, "workspace_half_m");
  positive(max_target_step_m, "max_target_step_m");
  positive(max_force_step_n, "max_force_step_n");
  positive(watchdog_ramp_s, "watchdog_ramp_s");
  positive(clock_stall_s, "clock_stall_s");
  positive(max_tick_gap_s, "max_tick_gap_s");
  positive(recover_ramp_s, "recover_ramp_s");
  if (!(recover_after_s >= 0)) throw UsageError("safety recover_after_s must be >= 0");
  if (max_force_n > 9.0)
    throw UsageError("safety max_force_n above 9 N exceeds what a Falcon may be commanded");
  if (workspace_half_m > 0.05)
    throw UsageError("safety workspace_half_m above 0.05 m leaves the 0.10 m cube");
  if (watchdog_ramp_s > 0.02) throw UsageError("safety watchdog_ramp_s must be <= 0.02 s");
}

ActuatorSafety::ActuatorSafety(const SafetyOptions& options, double device_max_force_n)
    : o_(options),
      max_force_n_(std::isfinite(device_max_force_n) && device_max_force_n > 0
                       ? std::min(options.max_force_n, device_max_force_n)
                       : 0.0) {}

void ActuatorSafety::ResetTarget(const Eigen::Vector3d& pos_m) noexcept {
  if (!pos_m.allFinite()) return;
  last_target_m_ = pos_m.cwiseMax(-o_.workspace_half_m).cwiseMin(o_.workspace_half_m);
}

Eigen::Vector3d ActuatorSafety::FilterTarget(const Eigen::Vector3d& target_m) noexcept {
  if (!target_m.allFinite()) {
    tick_faults_ |= kFaultNonFiniteTarget;
    faults_ |= kFaultNonFiniteTarget;
    return last_target_m_;
  }
  Eigen::Vector3d t = target_m;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > o_.workspace_half_m) {
      tick_faults_ |= kFaultTargetClamped;
      faults_ |= kFaultTargetClamped;
      t[i] = std::copysign(o_.workspace_half_m, t[i]);
    }
  }
  Eigen::Vector3d step = t - last_target_m_;
  const double n = step.norm();
  if (n > o_.max_target_step_m) step *= o_.max_target_step_m / n;
  last_target_m_ += step;
  return last_target_m_;
}

Eigen::Vector3d ActuatorSafety::FilterForce(const Eigen::Vector3d& force_n, double gain) noexcept {
  if (!force_n.allFinite() || !std::isfinite(gain)) {
    tick_faults_ |= kFaultNonFiniteForce;
    faults_ |= kFaultNonFiniteForce;
    last_force_n_.setZero();
    last_out_n_.setZero();
    return Eigen::Vector3d::Zero();
  }
  Eigen::Vector3d f = force_n;
  // Norm without overflow: 1e300 squared is inf.
  const double scale = f.cwiseAbs().maxCoeff();
  const double norm = scale > 0 ? scale * (f / scale).norm() : 0.0;
  if (norm > max_force_n_) {
    tick_faults_ |= kFaultForceClamped;
    faults_ |= kFaultForceClamped;
    f = norm > 0 ? Eigen::Vector3d((f / scale) * (max_force_n_ / (norm / scale)))
                 : Eigen::Vector3d::Zero();
  }
  Eigen::Vector3d df = f - last_force_n_;
  const double dn = df.norm();
  if (dn > o_.max_force_step_n) df *= o_.max_force_step_n / dn;
  last_force_n_ += df;
  Eigen::Vector3d out = last_force_n_ * std::clamp(gain, 0.0, 1.0);
  // The gain may rise (watchdog recovery): an output whose magnitude grows
  // is rate-limited too. Shrinking towards zero is the safe direction and
  // passes (that is how the watchdog meets its 20 ms).
  if (out.norm() > last_out_n_.norm()) {
    Eigen::Vector3d dout = out - last_out_n_;
    const double don = dout.norm();
    if (don > o_.max_force_step_n) out = last_out_n_ + dout * (o_.max_force_step_n / don);
  }
  // Final guard: whatever happened above, never above the limit, never NaN.
  const double on = out.norm();
  if (!std::isfinite(on)) {
    last_out_n_.setZero();
    return Eigen::Vector3d::Zero();
  }
  if (on > max_force_n_) out *= max_force_n_ / on;
  last_out_n_ = out;
  return out;
}

double Watchdog::Update(double dt_s, bool healthy) noexcept {
  if (!std::isfinite(dt_s) || dt_s < 0) dt_s = 0, healthy = false;
  if (!healthy) {
    if (!tripped_) ++trips_;
    tripped_ = true;
    healthy_for_s_ = 0;
    // Ramp down in at most watchdog_ramp_s: count the ramp in ticks at
    // least as long as the tick itself so a long gap drops to zero at once.
    gain_ = gain_ - std::max(dt_s, 1e-6) / o_.watchdog_ramp_s;
    if (gain_ < 1e-9) gain_ = 0;
    return gain_;
  }
  if (tripped_) {
    healthy_for_s_ += dt_s;
    if (healthy_for_s_ < o_.recover_after_s) {
      gain_ = gain_ - std::max(dt_s, 1e-6) / o_.watchdog_ramp_s;
      if (gain_ < 1e-9) gain_ = 0;
      return gain_;
    }
    tripped_ = false;
  }
  gain_ = std::min(1.0, gain_ + dt_s / o_.recover_ramp_s);
  return gain_;
}

}  // namespace hapcine
