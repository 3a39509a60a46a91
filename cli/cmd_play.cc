// `hapcine play`: a film with its haptic track on the HapSeat (player/play.h).
#include <iostream>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/output_files.h"
#include "player/play.h"

namespace hapcine::cli {

int RunPlay(int argc, char** argv) {
  CLI::App app{
      "Play a video with its haptic track on the HapSeat (three Falcons, or a simulation).\n"
      "The 1 kHz loop renders F = k (G' - P) - d V (Eq. 7) per actuator through the safety layer.\n"
      "mpv's keys work in the window: space pause, arrows seek, f full screen, q quit.",
      "hapcine play"};
  PlayOptions o;
  app.add_option("video", o.video, "The video file (played by mpv)")->required(false);
  app.add_option("--track", o.track,
                 "Haptic track (*.haptic.csv, or an MPEG-I Haptics .hjif with Position perceptions). "
                 "Default: <video stem>.haptic.csv beside the video");
  app.add_option("--device", o.device, "falcon (Novint Falcons over USB), sim (simulated) or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"falcon", "sim", "none"}));
  app.add_flag("--headless", o.headless,
               "No window or sound (mpv vo=null, ao=null); exits at the end of the film");
  app.add_flag("--no-video", o.wall_clock,
               "Do not run mpv at all: media time is the wall clock from start (needs --track or "
               "VIDEO's sibling track)");
  app.add_flag("--fullscreen", o.fullscreen, "Start mpv full screen");
  app.add_option("--k", o.loop.k_n_m, "Spring constant k of Eq. 7, N/m")->capture_default_str()
      ->check(FiniteRange(0, 3000));
  app.add_option("--d", o.loop.d_n_s_m, "Damping constant d of Eq. 7, N s/m")
      ->capture_default_str()
      ->check(FiniteRange(0, 50));
  app.add_option("--max-force", o.loop.safety.max_force_n,
                 "Force limit per actuator, N (at most 9)")
      ->capture_default_str()
      ->check(FiniteRange(0, 9));
  app.add_option("--firmware", o.firmware,
                 "Falcon firmware image (your copy of Novint's nVent_firmware.bin); loaded if not "
                 "already running");
  app.add_option("--seat-config", o.seat_config,
                 "JSON mapping Falcon serial numbers to head/left/right (docs/player.md). Default: "
                 "serial order");
  app.add_flag("--stats", o.print_stats,
               "Print loop statistics at the end (period p50/p99/max, missed ticks, sync)");
  app.add_option("--duration-tolerance", o.duration_tolerance_s,
                 "Warn when the track and video lengths differ by more than this, s")
      ->capture_default_str()
      ->check(FiniteRange(0, 3600));
  app.add_flag("--strict-duration", o.strict_duration,
               "Make a track/video length mismatch an error");
  bool no_rt = false;
  app.add_flag("--no-realtime", no_rt, "Do not try SCHED_FIFO for the loop thread");
  app.add_option("--fault-log", o.fault_log, "Where the last 2048 ticks are written after a fault")
      ->capture_default_str();
  return RunApp(app, argc, argv, [&] {
    o.realtime = !no_rt;
    // Checked up front; the fault log itself is committed when a fault writes it.
    CheckOutputPaths({{o.video, "VIDEO"}, {o.track, "--track"}, {o.firmware, "--firmware"},
                      {o.seat_config, "--seat-config"}},
                     {{o.fault_log, "--fault-log"}});
    const PlayResult r = Play(o, std::cerr);
    // Stopped by SIGINT/SIGTERM (forces zeroed): the shell's 128 + signal.
    return r.stop_signal > 0 ? 128 + r.stop_signal : kExitOk;
  });
}

}  // namespace hapcine::cli
