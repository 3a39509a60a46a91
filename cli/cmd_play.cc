#include "cli/command.h"

namespace hapcine::cli {

int RunPlay(int argc, char** argv) {
  return NotYetImplemented("play", "playback with haptics", argc, argv);
}

}  // namespace hapcine::cli
