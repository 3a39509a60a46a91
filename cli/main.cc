// hapcine: haptic feedback from the camera motion of ordinary films.
//   video -> extract -> estimate -> camera path -> haptics -> haptic track -> play

#include <cstring>
#include <iostream>
#include <string>

#include "cli/command.h"
#include "core/error_message.h"
#include "core/output_files.h"
#include "estimate/bundle/solver_log.h"

namespace {

struct Subcommand {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);
};

const Subcommand kSubcommands[] = {
    {"synth", "render synthetic clips (the paper's seven effects, hard cases) with ground truth",
     hapcine::cli::RunSynth},
    {"estimate", "recover the camera path (rotation, translation, zoom) from a video",
     hapcine::cli::RunEstimate},
    {"haptics", "turn a camera path (or video) into a haptic track", hapcine::cli::RunHaptics},
    {"play", "play a video with its haptic track on the HapSeat (falcon, sim or none)",
     hapcine::cli::RunPlay},
    {"preview", "render a video with an inset showing the actuators", hapcine::cli::RunPreview},
    {"eval", "compare an estimated camera path against ground truth", hapcine::cli::RunEval},
    {"plot", "draw camera paths and haptic tracks as PNG and SVG", hapcine::cli::RunPlot},
    {"make", "film in, camera path and haptic track out, in one command (reuses the camera path)",
     hapcine::cli::RunMake},
    {"batch", "process a whole video library, locally or on Slurm", hapcine::cli::RunBatch},
    {"studio", "review and edit a film's haptics in the browser (local web server)",
     hapcine::cli::RunStudio},
    {"study", "plan, run and analyse a pairwise user study", hapcine::cli::RunStudy},
    {"convert",
     "convert camera paths to and from TUM and COLMAP; export to KITTI, Nuke .chan, Blender",
     hapcine::cli::RunConvert},
};

void PrintUsage(std::ostream& out) {
  out << "hapcine — haptic feedback from the camera motion of ordinary films\n\n"
         "Usage: hapcine <command> [options]    (hapcine <command> --help for details)\n\n"
         "Commands:\n";
  for (const auto& c : kSubcommands) {
    out << "  " << c.name << std::string(10 - std::strlen(c.name), ' ') << c.summary << "\n";
  }
  out << "\nData flow: video -> estimate -> *.camera.csv -> haptics -> *.haptic.csv -> play\n"
         "Exit codes: 0 success, 1 failure (the message names the file and the reason), 2 usage.\n";
}

}  // namespace

int main(int argc, char** argv) {
  // SIGINT/SIGTERM/SIGHUP remove the temporaries of unfinished outputs.
  hapcine::InstallTempCleanupOnSignals();
  hapcine::QuietSolverLog();  // Ceres' recoverable warnings stay off the progress lines
  if (argc < 2) {
    PrintUsage(std::cerr);
    return hapcine::cli::kExitUsage;
  }
  const std::string cmd = argv[1];
  if (cmd == "-h" || cmd == "--help" || cmd == "help") {
    PrintUsage(std::cout);
    return 0;
  }
  if (cmd == "--version") {
    std::cout << "hapcine 0.1.0\n";
    return 0;
  }
  for (const auto& c : kSubcommands) {
    if (cmd == c.name) {
      std::string prog = std::string("hapcine ") + c.name;
      argv[1] = prog.data();
      // RunApp reports what the command's work throws; this catches what
      // escapes before it (setting up the options) as the same one line.
      try {
        return c.run(argc - 1, argv + 1);
      } catch (...) {
        std::cerr << prog << ": " << hapcine::EscapedExceptionMessage(std::current_exception())
                  << "\n";
        return hapcine::cli::kExitFailure;
      }
    }
  }
  std::cerr << "hapcine: unknown command '" << cmd << "'\n";
  PrintUsage(std::cerr);
  return hapcine::cli::kExitUsage;
}
