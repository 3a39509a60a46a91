#pragma once
// `hapcine haptics CAM --seat platform.json`: the motion-platform branch of
// the haptics command (platform/motion_cueing.h), chosen when the --seat
// file says "type": "platform".

#include <string>
#include <vector>

namespace hapcine::cli {

struct PlatformRunArgs {
  std::string seat_file, input, output, model;
  bool print_seat = false;
  double rate_hz = 0;            // 0 = the platform's rate_hz
  double reference_depth_u = 0;  // --reference-depth
  double max_gap_s = 1;          // --max-gap
  bool other_outputs = false;    // --hjif or --effects-out given (HapSeat only)
};

int RunPlatformHaptics(const PlatformRunArgs& args);

// True when words for `hapcine haptics` choose a motion platform (`--seat FILE`
// or `--seat=FILE` of "type": "platform"): make and batch then pass no edits
// file, which only the HapSeat models take.
bool ArgumentsChoosePlatform(const std::vector<std::string>& haptics_args);

}  // namespace hapcine::cli
