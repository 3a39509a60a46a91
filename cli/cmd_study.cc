#include "cli/command.h"

namespace hapcine::cli {

int RunStudy(int argc, char** argv) {
  return NotYetImplemented("study", "user study", argc, argv);
}

}  // namespace hapcine::cli
