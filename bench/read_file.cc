// hapcine_read_bench camera|haptic FILE: reads FILE with the library's
// reader and prints its row count; bench/memory.sh measures its peak RSS
// against the file's size (nothing else in the process).
#include <cstdio>
#include <cstring>
#include <exception>

#include "core/camera_path.h"
#include "core/haptic_track.h"

int main(int argc, char** argv) {
  if (argc != 3 || (std::strcmp(argv[1], "camera") != 0 && std::strcmp(argv[1], "haptic") != 0)) {
    std::fprintf(stderr, "usage: hapcine_read_bench camera|haptic FILE\n");
    return 2;
  }
  try {
    const size_t rows = std::strcmp(argv[1], "camera") == 0
                            ? hapcine::ReadCameraPathFile(argv[2]).frames.size()
                            : hapcine::ReadHapticTrackFile(argv[2]).samples.size();
    std::printf("%zu rows\n", rows);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_read_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
