// `hapcine preview`: the video with an inset of the three actuators
// (datasets/preview.h).

#include <filesystem>
#include <iostream>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "datasets/preview.h"
#include "player/simulate_seat.h"

namespace hapcine::cli {

int RunPreview(int argc, char** argv) {
  CLI::App app{
      "Render VIDEO with an inset showing the HapSeat's three actuators following the haptic "
      "track\n"
      "(top view of each 0.10 m workspace with a 1 s trail, and a gauge for height): the target\n"
      "as a dot and, unless --no-sim, the simulated grip (sim device, Eq. 7 loop) as a ring.\n"
      "The film's sound is kept (copied, or AAC where MP4 cannot hold it) and the timecode,\n"
      "shot, camera model and semantic effect are burnt in top-left. --from/--to render a\n"
      "range (seconds or HH:MM:SS:FF), sound included. Details: docs/haptics.md \"Preview\".",
      "hapcine preview"};
  PreviewOptions o;
  app.add_option("video", o.video, "The video file")->required();
  app.add_option("--track", o.track,
                 "Haptic track (*.haptic.csv). Default: <video stem>.haptic.csv beside the video");
  app.add_option("-o,--output", o.output, "Output MP4 (H.264), written atomically")->required();
  app.add_option("--camera", o.camera,
                 "Camera path (*.camera.csv) for the burnt-in shot, camera model and (for a track\n"
                 "without an effect column) the classifier's effects. Default: <video stem>.camera.csv\n"
                 "beside the video when it exists");
  app.add_option("--from", o.from,
                 "Start of the range: seconds (62.5) or timecode HH:MM:SS:FF at the film's rate");
  app.add_option("--to", o.to, "End of the range (excluded), as --from. Default: the end");
  bool no_burn_in = false, no_audio = false;
  app.add_flag("--no-burn-in", no_burn_in, "No timecode, shot, camera model or effect text");
  app.add_flag("--no-audio", no_audio, "A silent preview, even of a film with sound");
  app.add_option("--platform", o.platform_track,
                 "Draw a motion platform track (*.platform.csv, from `hapcine haptics --seat\n"
                 "platform.json`) instead of the HapSeat: a seat that moves, seen from behind,\n"
                 "from its right side and from above, over its home pose; unless --no-sim,\n"
                 "a simulated platform (drives of 3 Hz, damping 0.7) in light blue");
  app.add_option("--max-side", o.max_side, "Longest side of the output in pixels (0 = as decoded)")
      ->capture_default_str()
      ->check(FiniteRange(0, 16384));
  app.add_option("--inset", o.inset_fraction, "Inset width as a fraction of the frame width")
      ->capture_default_str()
      ->check(FiniteRange(0.15, 1));
  app.add_option("--trail", o.trail_s, "Trail length, seconds")->capture_default_str()
      ->check(FiniteRange(0, 10));
  app.add_option("--crf", o.crf, "x264 quality (0 best .. 51 worst)")->capture_default_str()
      ->check(FiniteRange(0, 51));
  bool no_sim = false;
  app.add_flag("--no-sim", no_sim, "Draw the targets only, not the simulated grips");
  LoopOptions loop;
  app.add_option("--k", loop.k_n_m, "Spring constant k of Eq. 7 for the simulation, N/m")
      ->capture_default_str()
      ->check(FiniteRange(0, 3000));
  app.add_option("--d", loop.d_n_s_m, "Damping constant d of Eq. 7 for the simulation, N s/m")
      ->capture_default_str()
      ->check(FiniteRange(0, 50));
  return RunApp(app, argc, argv, [&] {
    o.simulate_platform = !no_sim && !o.platform_track.empty();
    o.burn_in = !no_burn_in;
    o.audio = !no_audio;
    if (!no_sim) {
      loop.Check();
      o.simulate = [&loop](const HapticTrack& t) { return SimulateSeat(t, loop); };
    }
    // The default track is the video's sibling <stem>.haptic.csv.
    const std::filesystem::path v(o.video);
    const std::string track = o.track.empty()
                                  ? (v.parent_path() / (v.stem().string() + ".haptic.csv")).string()
                                  : o.track;
    OutputSet outputs({{o.video, "VIDEO"}, {o.platform_track.empty() ? track : o.track, "--track"},
                       {o.platform_track, "--platform"}, {o.camera, "--camera"}},
                      {{o.output, "-o"}});
    Progress progress(std::cerr, ProgressModeFor(false), "preview", "frames");
    const int n = RenderPreview(o, [&](int done, int total) { progress.Update(done, total); });
    progress.Close();
    outputs.CommitAll();
    std::cerr << "wrote " << o.output << " (" << n << " frames)\n";
    return kExitOk;
  });
}

}  // namespace hapcine::cli
