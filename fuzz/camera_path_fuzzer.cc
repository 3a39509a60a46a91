// The camera-path reader (core/camera_path.h) on arbitrary bytes; what it
// accepts must also be writable.
#include <sstream>

#include "core/camera_path.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hapcine::fuzz::AcceptOnlyError([&] {
    std::istringstream in(hapcine::fuzz::AsString(data, size));
    const hapcine::CameraPath path = hapcine::ReadCameraPath(in, "fuzz.camera.csv");
    std::ostringstream out;
    hapcine::WriteCameraPath(path, out);
  });
  return 0;
}
