#pragma once
// The HapSeat's response to a track, offline: the 1 kHz loop (Equation 7,
// safety layer, start/end ramps) driving three simulated Falcons with a hand
// on each, stepped synchronously along the track's own time. The result is a
// HapticTrack of where each grip actually was, so the film preview can show
// the actuators moving (with their lag and overshoot) beside the targets.

#include "core/haptic_track.h"
#include "haptics/sim_device.h"
#include "player/haptic_loop.h"

namespace hapcine {

// Positions of the three simulated grips from 0 to the track's end plus the
// end ramp, recorded at record_hz (seat frame, metres). Deterministic.
// Throws UsageError on bad options, Error on an empty track.
HapticTrack SimulateSeat(const HapticTrack& track, const LoopOptions& loop = LoopOptions(),
                         const SimDeviceOptions& sim = SimDeviceOptions(),
                         double record_hz = 100);

}  // namespace hapcine
