// The two motion-platform readers on the same bytes: the platform file
// (platform/platform_config.h, `--seat platform.json`) and the platform
// track (platform/platform_track.h, `preview --platform`, `plot platform`).
// What they accept must write back, and an accepted config must read its own
// JSON and drive the safety clamp.
#include <sstream>

#include "fuzz/fuzz_input.h"
#include "platform/platform_config.h"
#include "platform/platform_safety.h"
#include "platform/platform_track.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = hapcine::fuzz::AsString(data, size);
  hapcine::fuzz::AcceptOnlyError([&] {
    const hapcine::PlatformConfig c = hapcine::ParsePlatformJson(text, "fuzz.platform.json");
    hapcine::ParsePlatformJson(hapcine::PlatformConfigToJson(c), "again.platform.json");
    hapcine::PlatformSafety safety(c, c.rate_hz);
    for (double v : {0.0, 1e6, -1e6, 0.0}) safety.Step(hapcine::PlatformPose::Constant(v));
  });
  hapcine::fuzz::AcceptOnlyError([&] {
    std::istringstream in(text);
    const hapcine::PlatformTrack track = hapcine::ReadPlatformTrack(in, "fuzz.platform.csv");
    std::ostringstream out;
    hapcine::WritePlatformTrack(track, out);
  });
  return 0;
}
