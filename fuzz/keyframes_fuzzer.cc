// The keyframe (hand-placed effects) reader, haptics/keyframes.h.
#include <sstream>

#include "fuzz/fuzz_input.h"
#include "haptics/keyframes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hapcine::fuzz::AcceptOnlyError([&] {
    std::istringstream in(hapcine::fuzz::AsString(data, size));
    const auto segments = hapcine::ReadKeyframes(in, "fuzz.keyframes.csv");
    std::ostringstream out;
    hapcine::WriteKeyframes(segments, out);
  });
  return 0;
}
