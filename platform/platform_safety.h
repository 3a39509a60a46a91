#pragma once
// The last stage every platform pose passes: nothing reaches a track file
// (or a platform) without it (MakePlatformTrack runs it on every sample,
// VerifyPlatformTrack re-checks the result before it is written).
//
// Per degree of freedom, sample by sample at the track's rate (dt):
//  - a non-finite target is replaced by the previous pose (counted);
//  - velocity moves towards (target - previous) / dt by at most
//    acceleration * dt, is held within +-velocity, and within the braking
//    bound towards each end of +-position: with steps of acceleration * dt
//    the platform can always stop before the end (discrete braking curve
//    v <= a dt (sqrt(1/4 + 2 d / (a dt^2)) - 1/2), d = distance to the end),
//    so position, velocity and acceleration limits all hold, from rest;
//  - disabled DOFs stay at 0;
//  - Stewart platform: a pose is taken only if the legs are within their
//    stroke there and all along a full brake from it (every DOF decelerating
//    at its limit); otherwise the platform brakes, which the previous
//    sample's check proved stays inside. So no pose needs a leg out of
//    stroke, and the acceleration limit holds. Should rounding ever defeat
//    that, the step is scaled back towards the previous pose (inside) until
//    every leg is inside, and counted (stroke_limited_samples): a pose out
//    of stroke is never output.

#include <cstddef>

#include "platform/platform_config.h"
#include "platform/stewart.h"

namespace hapcine {

struct SafetyCounts {
  size_t clamped = 0;        // samples where the output differs from the target (> 1e-9)
  size_t nonfinite = 0;      // samples whose target was not finite
  size_t stroke_limited = 0; // samples scaled back into the leg stroke
};

class PlatformSafety {
 public:
  // Starts at rest at the home pose. Throws UsageError on a bad config.
  PlatformSafety(const PlatformConfig& config, double rate_hz);
  // The safe pose for the next sample.
  PlatformPose Step(const PlatformPose& target);
  const SafetyCounts& counts() const { return counts_; }

 private:
  PlatformPose StepDofs(const PlatformPose& target) const;
  PlatformPose KeepLegsInStroke(const PlatformPose& pose);
  PlatformPose Braked(const PlatformPose& velocity) const;
  bool BrakeStaysInStroke(PlatformPose pose, PlatformPose velocity) const;

  PlatformConfig config_;
  double dt_;
  PlatformPose pose_ = PlatformPose::Zero();
  PlatformPose velocity_ = PlatformPose::Zero();
  SafetyCounts counts_;
};

// Largest |value| / limit over a track, from rest at home before the first
// sample (velocity and acceleration by differences at the track's rate).
struct PlatformLimitCheck {
  double position_ratio = 0;
  double velocity_ratio = 0;
  double acceleration_ratio = 0;
  double disabled_max = 0;      // largest |pose| of a DOF the platform does not have
  bool legs_in_stroke = true;   // Stewart: every sample's legs inside [min, max]
  bool finite = true;
};
struct PlatformTrack;
PlatformLimitCheck MeasurePlatformLimits(const PlatformTrack& track, const PlatformConfig& config);
// Throws Error("platform track", reason) unless positions, velocities and
// legs are within the limits (1e-6 relative tolerance for rounding), every
// value is finite and disabled DOFs are 0: run before a track is written.
void VerifyPlatformTrack(const PlatformTrack& track, const PlatformConfig& config);

// Velocity that can still stop within distance d with decrements a * dt.
double BrakingSpeed(double distance, double accel, double dt);

}  // namespace hapcine
