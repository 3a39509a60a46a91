#include "cli/command.h"

namespace hapcine::cli {

int RunEstimate(int argc, char** argv) {
  return NotYetImplemented("estimate", "camera path from video", argc, argv);
}

}  // namespace hapcine::cli
