#include "platform/sim_platform.h"

#include <cmath>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {

void SimPlatformOptions::Check() const {
  if (!(natural_hz > 0 && natural_hz <= 100)) throw UsageError("sim platform: natural_hz must be in (0, 100]");
  if (!(damping > 0 && damping <= 10)) throw UsageError("sim platform: damping must be in (0, 10]");
  if (!(step_hz >= 10 * natural_hz && step_hz <= 100000))
    throw UsageError("sim platform: step_hz must be >= 10 x natural_hz and <= 100000");
}

PlatformTrack SimulatePlatform(const PlatformTrack& targets, const SimPlatformOptions& o) {
  o.Check();
  PlatformTrack out = targets;
  out.model = "simulated";
  if (targets.samples.empty()) return out;
  const double w = 2 * kPi * o.natural_hz, dt = 1.0 / o.step_hz;
  PlatformPose x = PlatformPose::Zero(), v = PlatformPose::Zero();
  double t = targets.samples.front().time_s;
  for (size_t i = 0; i < targets.samples.size(); ++i) {
    const PlatformSample& s = targets.samples[i];
    // Semi-implicit Euler towards the previous sample's target (a zero-order
    // hold of the commands, as a drive receives them).
    const PlatformPose& target = targets.samples[i > 0 ? i - 1 : 0].pose;
    while (t + 0.5 * dt < s.time_s) {
      v += dt * (w * w * (target - x) - 2 * o.damping * w * v);
      x += dt * v;
      t += dt;
    }
    out.samples[i].pose = x;
    out.samples[i].legs.reset();
  }
  return out;
}

}  // namespace hapcine
