#include "cli/command.h"

namespace hapcine::cli {

int RunSynth(int argc, char** argv) {
  return NotYetImplemented("synth", "render synthetic clips", argc, argv);
}

}  // namespace hapcine::cli
