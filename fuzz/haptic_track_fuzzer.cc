// The haptic-track reader (core/haptic_track.h) on arbitrary bytes; what it
// accepts must also be writable and sampled (the player's 1 kHz lookup).
#include <sstream>

#include "core/haptic_track.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hapcine::fuzz::AcceptOnlyError([&] {
    std::istringstream in(hapcine::fuzz::AsString(data, size));
    const hapcine::HapticTrack track = hapcine::ReadHapticTrack(in, "fuzz.haptic.csv");
    Eigen::Vector3d pos[hapcine::kNumActuators];
    size_t hint = 0;
    for (double t : {-1.0, 0.0, 0.5 * track.duration_s(), track.duration_s(), 1e9})
      track.Sample(t, pos, &hint);
    std::ostringstream out;
    hapcine::WriteHapticTrack(track, out);
  });
  return 0;
}
