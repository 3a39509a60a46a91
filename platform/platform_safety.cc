#include "platform/platform_safety.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "platform/platform_track.h"

namespace hapcine {

// Braking from v = c a dt with decrements of a dt (the last one may be
// smaller) covers S(c) = a dt^2 * sum_{i=0}^{m-1} (c - i), m = ceil(c) steps,
// i.e. a dt^2 (m c - m (m - 1) / 2). The bound is the c with S(c) = d: the
// smallest m with m (m + 1) / 2 >= d / (a dt^2), then c from S. Moving at
// at most this speed leaves room to brake at the next sample (c - 1 >= the
// next bound's c), so the invariant holds from rest.
double BrakingSpeed(double distance, double accel, double dt) {
  if (!(distance > 0)) return 0;
  const double units = distance / (accel * dt * dt);
  double m = std::max(1.0, std::ceil(0.5 * (std::sqrt(1 + 8 * units) - 1) - 1e-12));
  while (m * (m + 1) / 2 < units) m += 1;  // rounding of the square root
  const double c = std::min(m, (units + m * (m - 1) / 2) / m);
  return c * accel * dt;
}

PlatformSafety::PlatformSafety(const PlatformConfig& config, double rate_hz)
    : config_(config), dt_(1.0 / rate_hz) {
  config_.Check();
  if (!(rate_hz >= 10 && rate_hz <= 10000)) throw UsageError("platform: rate must be in [10, 10000] Hz");
}

PlatformPose PlatformSafety::StepDofs(const PlatformPose& target) const {
  PlatformPose out = PlatformPose::Zero();
  for (int d = 0; d < kNumDofs; ++d) {
    if (!config_.enabled[d]) continue;
    const DofLimits& l = config_.limits[d];
    const double dv = l.acceleration * dt_;
    double v = (target[d] - pose_[d]) / dt_;
    v = std::clamp(v, velocity_[d] - dv, velocity_[d] + dv);
    v = std::clamp(v, -l.velocity, l.velocity);
    // Position safety comes first: the braking bounds win over the rest.
    const double up = BrakingSpeed(l.position - pose_[d], l.acceleration, dt_);
    const double down = BrakingSpeed(l.position + pose_[d], l.acceleration, dt_);
    v = std::clamp(v, -down, up);
    out[d] = std::clamp(pose_[d] + v * dt_, -l.position, l.position);
  }
  return out;
}

// The velocity one sample later when every DOF brakes as hard as allowed.
PlatformPose PlatformSafety::Braked(const PlatformPose& velocity) const {
  PlatformPose out = velocity;
  for (int d = 0; d < kNumDofs; ++d) {
    const double dv = config_.limits[d].acceleration * dt_;
    out[d] = velocity[d] > 0 ? std::max(0.0, velocity[d] - dv) : std::min(0.0, velocity[d] + dv);
  }
  return out;
}

// Whether `pose`, and every pose of a full brake from it at `velocity`, has
// its legs within the stroke.
bool PlatformSafety::BrakeStaysInStroke(PlatformPose pose, PlatformPose velocity) const {
  const StewartGeometry& g = *config_.stewart;
  constexpr int kMaxSteps = 100000;
  for (int i = 0; i < kMaxSteps; ++i) {
    if (!LegsWithinStroke(g, StewartLegLengths(g, pose))) return false;
    velocity = Braked(velocity);
    if (velocity.isZero()) return true;
    pose += velocity * dt_;
  }
  return false;
}

// A Stewart platform moves to `pose` only if it can still stop with every
// leg inside; else it brakes (the braking path was checked one sample ago,
// so it is inside and within every limit). The last resort, should rounding
// defeat that, scales the step back towards the previous pose (counted).
PlatformPose PlatformSafety::KeepLegsInStroke(const PlatformPose& pose) {
  if (BrakeStaysInStroke(pose, (pose - pose_) / dt_)) return pose;
  const PlatformPose braked = pose_ + Braked(velocity_) * dt_;
  const StewartGeometry& g = *config_.stewart;
  if (LegsWithinStroke(g, StewartLegLengths(g, braked))) return braked;
  ++counts_.stroke_limited;
  double lo = 0, hi = 1;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    const PlatformPose p = pose_ + mid * (braked - pose_);
    (LegsWithinStroke(g, StewartLegLengths(g, p)) ? lo : hi) = mid;
  }
  return pose_ + lo * (braked - pose_);
}

PlatformPose PlatformSafety::Step(const PlatformPose& target_in) {
  PlatformPose target = target_in;
  if (!target.allFinite()) {
    ++counts_.nonfinite;
    target = pose_;
  }
  PlatformPose next = StepDofs(target);
  if (config_.stewart) next = KeepLegsInStroke(next);
  if ((next - target).cwiseAbs().maxCoeff() > 1e-9) ++counts_.clamped;
  velocity_ = (next - pose_) / dt_;
  pose_ = next;
  return next;
}

PlatformLimitCheck MeasurePlatformLimits(const PlatformTrack& track, const PlatformConfig& cfg) {
  PlatformLimitCheck c;
  const double dt = 1.0 / track.rate_hz;
  PlatformPose prev = PlatformPose::Zero(), prev_v = PlatformPose::Zero();
  for (const PlatformSample& s : track.samples) {
    c.finite &= s.pose.allFinite();
    const PlatformPose v = (s.pose - prev) / dt;
    const PlatformPose a = (v - prev_v) / dt;
    for (int d = 0; d < kNumDofs; ++d) {
      if (!cfg.enabled[d]) {
        c.disabled_max = std::max(c.disabled_max, std::abs(s.pose[d]));
        continue;
      }
      const DofLimits& l = cfg.limits[d];
      c.position_ratio = std::max(c.position_ratio, std::abs(s.pose[d]) / l.position);
      c.velocity_ratio = std::max(c.velocity_ratio, std::abs(v[d]) / l.velocity);
      c.acceleration_ratio = std::max(c.acceleration_ratio, std::abs(a[d]) / l.acceleration);
    }
    if (cfg.stewart) {
      c.legs_in_stroke &= LegsWithinStroke(*cfg.stewart, StewartLegLengths(*cfg.stewart, s.pose));
    }
    prev = s.pose;
    prev_v = v;
  }
  return c;
}

void VerifyPlatformTrack(const PlatformTrack& track, const PlatformConfig& cfg) {
  const PlatformLimitCheck c = MeasurePlatformLimits(track, cfg);
  constexpr double kTolerance = 1 + 1e-6;
  if (!c.finite) throw Error("platform track", "non-finite pose");
  if (c.position_ratio > kTolerance) throw Error("platform track", "a position limit is exceeded");
  if (c.velocity_ratio > kTolerance) throw Error("platform track", "a velocity limit is exceeded");
  if (!c.legs_in_stroke) throw Error("platform track", "a leg is out of its stroke");
  if (c.disabled_max > 0) throw Error("platform track", "a DOF the platform does not have moves");
}

}  // namespace hapcine
