#include "cli/command.h"

namespace hapcine::cli {

int RunPreview(int argc, char** argv) {
  return NotYetImplemented("preview", "video with an actuator inset", argc, argv);
}

}  // namespace hapcine::cli
