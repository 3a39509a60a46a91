// hapcine_track_rate_error REFERENCE.haptic.csv STORED.haptic.csv [--seat]:
// how far the positions a player renders from STORED (any rate, its own
// interpolation) are from those it renders from REFERENCE (the 1 kHz track).
//   targets: both tracks sampled with HapticTrack::Sample, the loop's own
//            function, at every row of REFERENCE and half-way between rows
//            (a 1 kHz loop at either phase);
//   --seat:  also the grips' positions when the player's loop (Eq. 7, the
//            safety layer, ramps) drives the simulated seat with each track
//            (player/simulate_seat.h), recorded at 1 kHz.
// Prints the largest distance per actuator and over all, in millimetres
// (docs/haptics.md, "Stored rate").
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "core/haptic_track.h"
#include "player/simulate_seat.h"

namespace {

using hapcine::HapticTrack;
using hapcine::kNumActuators;

void Compare(const HapticTrack& ref, const HapticTrack& stored, double max_m[kNumActuators],
             double* worst_t) {
  size_t hint_ref = 0, hint_stored = 0;
  Eigen::Vector3d a[kNumActuators], b[kNumActuators];
  const auto& s = ref.samples;
  for (size_t i = 0; i < s.size(); ++i) {
    for (double phase : {0.0, 0.5}) {
      if (phase > 0 && i + 1 == s.size()) break;
      const double t = phase > 0 ? 0.5 * (s[i].time_s + s[i + 1].time_s) : s[i].time_s;
      ref.Sample(t, a, &hint_ref);
      stored.Sample(t, b, &hint_stored);
      for (int k = 0; k < kNumActuators; ++k) {
        const double d = (a[k] - b[k]).norm();
        if (d > std::max({max_m[0], max_m[1], max_m[2]})) *worst_t = t;
        max_m[k] = std::max(max_m[k], d);
      }
    }
  }
}

// The grips of the simulated seat driven by each track, compared row by row.
double SeatDifferenceM(const HapticTrack& ref, const HapticTrack& stored) {
  const HapticTrack a = hapcine::SimulateSeat(ref, hapcine::LoopOptions(),
                                              hapcine::SimDeviceOptions(), 1000);
  const HapticTrack b = hapcine::SimulateSeat(stored, hapcine::LoopOptions(),
                                              hapcine::SimDeviceOptions(), 1000);
  double worst = 0;
  for (size_t i = 0; i < a.samples.size() && i < b.samples.size(); ++i) {
    for (int k = 0; k < kNumActuators; ++k) {
      worst = std::max(worst, (a.samples[i].pos_m[k] - b.samples[i].pos_m[k]).norm());
    }
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const bool seat = argc == 4 && std::string(argv[3]) == "--seat";
  if (argc != 3 && !seat) {
    std::fprintf(stderr,
                 "usage: hapcine_track_rate_error REFERENCE.haptic.csv STORED.haptic.csv [--seat]\n");
    return 2;
  }
  try {
    const HapticTrack ref = hapcine::ReadHapticTrackFile(argv[1]);
    const HapticTrack stored = hapcine::ReadHapticTrackFile(argv[2]);
    double max_m[kNumActuators] = {0, 0, 0};
    double worst_t = 0;
    Compare(ref, stored, max_m, &worst_t);
    const double all = std::max({max_m[0], max_m[1], max_m[2]});
    std::printf("%s at %g Hz (%s) vs %g Hz: max |difference| %.4f mm (head %.4f, left %.4f, "
                "right %.4f) at %.4f s\n",
                argv[2], stored.rate_hz, hapcine::TrackInterpolationName(stored.interpolation),
                ref.rate_hz, 1e3 * all, 1e3 * max_m[0], 1e3 * max_m[1], 1e3 * max_m[2], worst_t);
    if (seat) {
      std::printf("  simulated seat (loop, safety, grips at 1 kHz): max |difference| %.4f mm\n",
                  1e3 * SeatDifferenceM(ref, stored));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_track_rate_error: %s\n", e.what());
    return 1;
  }
  return 0;
}
