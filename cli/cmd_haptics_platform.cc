#include "cli/cmd_haptics_platform.h"

#include <iostream>

#include "cli/command.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/output_files.h"
#include "haptics/camera_signals.h"
#include "platform/motion_cueing.h"
#include "platform/platform_config.h"
#include "platform/platform_safety.h"

namespace hapcine::cli {

int RunPlatformHaptics(const PlatformRunArgs& a) {
  const PlatformConfig config = LoadPlatformFile(a.seat_file);
  if (a.print_seat) {
    std::cout << PlatformConfigToJson(config);
    return kExitOk;
  }
  if (a.input.empty()) throw UsageError("INPUT is required");
  if (a.output.empty()) throw UsageError("-o OUT.platform.csv is required");
  if (a.other_outputs) throw UsageError("--hjif and --effects-out are for the HapSeat, not a platform");
  if (a.input.size() < 4 || a.input.compare(a.input.size() - 4, 4, ".csv") != 0)
    throw UsageError("a motion platform takes a camera path (*.csv): run `hapcine estimate` first");
  OutputSet outputs({{a.input, "INPUT"}, {a.seat_file, "--seat"}}, {{a.output, "-o"}});
  PlatformOptions opt;
  opt.model = a.model;
  opt.rate_hz = a.rate_hz;
  opt.reference_depth_u = a.reference_depth_u;
  opt.source = a.input;
  opt.Check();
  const CameraPath path = ReadCameraPathFile(a.input);
  const std::vector<int> lines = CsvDataRowLines(a.input);
  ValidatePathForHaptics(path, a.input, a.max_gap_s, &lines);
  const InputScope making(a.input);
  const PlatformTrack track = MakePlatformTrack(path, config, opt);
  VerifyPlatformTrack(track, config);  // the clamp's result, checked again before it leaves
  AtomicFile csv(a.output);
  WritePlatformTrack(track, csv.stream());
  csv.Commit();
  outputs.CommitAll();
  std::cerr << "haptics: " << a.model << " platform track (" << config.name << ": "
            << track.dofs << ") of " << track.samples.size() << " samples ("
            << track.duration_s() << " s at " << track.rate_hz << " Hz) -> " << a.output
            << "; clamped samples: " << track.metadata.at("clamped_samples")
            << ", stroke-limited: " << track.metadata.at("stroke_limited_samples") << "\n";
  return kExitOk;
}

bool ArgumentsChoosePlatform(const std::vector<std::string>& args) {
  for (size_t i = 0; i < args.size(); ++i) {
    std::string seat;
    if (args[i] == "--seat" && i + 1 < args.size()) seat = args[i + 1];
    if (args[i].rfind("--seat=", 0) == 0) seat = args[i].substr(7);
    if (!seat.empty() && IsRegularFile(seat) && IsPlatformFile(seat)) return true;
  }
  return false;
}

}  // namespace hapcine::cli
