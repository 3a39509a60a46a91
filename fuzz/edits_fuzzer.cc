// The edits file reader (haptics/haptic_edits.h), which the studio also runs
// on request bodies: ParseHapticEdits, then for what it accepts the writer
// (its output must read back to the same edits) and MakeHapticTrack on a
// small three-shot path with those edits (a missing shot is an Error; the
// track never leaves the workspace).
#include <cmath>
#include <cstdlib>

#include "fuzz/fuzz_input.h"
#include "haptics/haptic_edits.h"
#include "haptics/haptic_models.h"

namespace {

// 3 shots of 1 s at 10 fps: a drift, a pan, a still.
const hapcine::CameraPath& SmallPath() {
  static const hapcine::CameraPath path = [] {
    hapcine::CameraPath p;
    for (int i = 0; i < 30; ++i) {
      hapcine::CameraFrame f;
      f.frame = i;
      f.time_s = i / 10.0;
      f.shot = i / 10;
      f.center = Eigen::Vector3d(i < 10 ? 0.05 * i : 0, 0, 0);
      const double pan = i >= 10 && i < 20 ? 0.02 * (i - 10) : 0;
      f.world_from_cam = Eigen::Quaterniond(std::cos(pan / 2), 0, std::sin(pan / 2), 0);
      f.fov_deg = 50;
      p.frames.push_back(f);
    }
    return p;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = hapcine::fuzz::AsString(data, size);
  hapcine::fuzz::AcceptOnlyError([&] {
    const hapcine::HapticEdits edits = hapcine::ParseHapticEdits(text, "fuzz.edits.json");
    if (!(hapcine::ParseHapticEdits(hapcine::HapticEditsToJson(edits), "again") == edits)) std::abort();
    hapcine::HapticOptions options;
    options.edits = edits;
    options.rate_hz = 20;  // small tracks: the fuzzer's time goes to the parser
    options.source = "fuzz.camera.csv";
    const hapcine::HapticTrack track = hapcine::MakeHapticTrack(SmallPath(), options);
    for (const hapcine::HapticSample& s : track.samples) {
      for (const Eigen::Vector3d& p : s.pos_m) {
        if (!(p.cwiseAbs().maxCoeff() <= options.seat.clamp_half_m)) std::abort();
      }
    }
  });
  return 0;
}
