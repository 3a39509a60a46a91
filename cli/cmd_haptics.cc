#include "cli/command.h"

namespace hapcine::cli {

int RunHaptics(int argc, char** argv) {
  return NotYetImplemented("haptics", "haptic track from a camera path", argc, argv);
}

}  // namespace hapcine::cli
