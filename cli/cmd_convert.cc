#include "cli/command.h"

namespace hapcine::cli {

int RunConvert(int argc, char** argv) {
  return NotYetImplemented("convert", "format conversion", argc, argv);
}

}  // namespace hapcine::cli
