#pragma once
// A simulated motion platform, for `hapcine preview --platform` (the
// platform's counterpart of player/simulate_seat.h): each DOF's drive is a
// position servo with second-order dynamics (natural frequency natural_hz,
// damping ratio damping) following the track's pose, integrated at step_hz
// and recorded at the track's samples. It shows the lag and overshoot a
// real platform's drives add to the commanded pose. The defaults (3 Hz,
// 0.7) are an assumption about a small electric platform, not a measured
// one: set them to your platform's.

#include "platform/platform_track.h"

namespace hapcine {

struct SimPlatformOptions {
  double natural_hz = 3.0;
  double damping = 0.7;
  double step_hz = 1000;
  void Check() const;  // throws UsageError
};

// Where the simulated platform is at each sample of `targets` (same times,
// no legs). Starts at rest at home at the first sample. Deterministic.
PlatformTrack SimulatePlatform(const PlatformTrack& targets, const SimPlatformOptions& options = {});

}  // namespace hapcine
