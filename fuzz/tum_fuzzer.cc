// The TUM trajectory reader (datasets/tum_format.h), then the conversion to a
// camera path that `hapcine convert --from-tum` makes of what it read.
#include <sstream>

#include "datasets/tum_format.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hapcine::fuzz::AcceptOnlyError([&] {
    std::istringstream in(hapcine::fuzz::AsString(data, size));
    const auto poses = hapcine::ReadTumTrajectory(in, "fuzz.tum.txt");
    hapcine::CameraPathFromTum(poses, 60);
  });
  return 0;
}
