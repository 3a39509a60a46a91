#include "cli/command.h"

namespace hapcine::cli {

int RunBatch(int argc, char** argv) {
  return NotYetImplemented("batch", "batch processing", argc, argv);
}

}  // namespace hapcine::cli
