#include "cli/command.h"

namespace hapcine::cli {

int RunPlot(int argc, char** argv) {
  return NotYetImplemented("plot", "plots", argc, argv);
}

}  // namespace hapcine::cli
