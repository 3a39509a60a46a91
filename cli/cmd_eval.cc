#include "cli/command.h"

namespace hapcine::cli {

int RunEval(int argc, char** argv) {
  return NotYetImplemented("eval", "compare camera paths", argc, argv);
}

}  // namespace hapcine::cli
