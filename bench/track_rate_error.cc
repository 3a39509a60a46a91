// hapcine_track_rate_error REFERENCE.haptic.csv STORED.haptic.csv: how far the
// positions a player renders from STORED (any rate, its own interpolation)
// are from those it renders from REFERENCE (the 1 kHz track): both tracks
// are sampled with HapticTrack::Sample, the player's function, at every row
// of REFERENCE and half-way between rows (a 1 kHz loop at either phase).
// Prints the largest distance per actuator and over all, in millimetres
// (docs/haptics.md, "Stored rate").
#include <algorithm>
#include <cstdio>
#include <exception>

#include "core/haptic_track.h"

namespace {

using hapcine::HapticTrack;
using hapcine::kNumActuators;

void Compare(const HapticTrack& ref, const HapticTrack& stored, double max_m[kNumActuators]) {
  size_t hint_ref = 0, hint_stored = 0;
  Eigen::Vector3d a[kNumActuators], b[kNumActuators];
  const auto& s = ref.samples;
  for (size_t i = 0; i < s.size(); ++i) {
    for (double phase : {0.0, 0.5}) {
      if (phase > 0 && i + 1 == s.size()) break;
      const double t = phase > 0 ? 0.5 * (s[i].time_s + s[i + 1].time_s) : s[i].time_s;
      ref.Sample(t, a, &hint_ref);
      stored.Sample(t, b, &hint_stored);
      for (int k = 0; k < kNumActuators; ++k) max_m[k] = std::max(max_m[k], (a[k] - b[k]).norm());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hapcine_track_rate_error REFERENCE.haptic.csv STORED.haptic.csv\n");
    return 2;
  }
  try {
    const HapticTrack ref = hapcine::ReadHapticTrackFile(argv[1]);
    const HapticTrack stored = hapcine::ReadHapticTrackFile(argv[2]);
    double max_m[kNumActuators] = {0, 0, 0};
    Compare(ref, stored, max_m);
    const double all = std::max({max_m[0], max_m[1], max_m[2]});
    std::printf("%s at %g Hz (%s) vs %g Hz: max |difference| %.4f mm (head %.4f, left %.4f, "
                "right %.4f)\n",
                argv[2], stored.rate_hz, hapcine::TrackInterpolationName(stored.interpolation),
                ref.rate_hz, 1e3 * all, 1e3 * max_m[0], 1e3 * max_m[1], 1e3 * max_m[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_track_rate_error: %s\n", e.what());
    return 1;
  }
  return 0;
}
