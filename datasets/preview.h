#pragma once
// `hapcine preview`: the film with an inset showing what the HapSeat's three
// actuators do, so a haptic track can be judged without a seat.
//
// For each frame at time t, the inset has three panels (head, left hand,
// right hand). Each panel is the actuator's 0.10 m workspace seen from above
// (X to the right, Z backward = down in the panel) with a dot at G'_A(t) and
// a fading trail of the last second, plus a vertical gauge for Y (up). When
// `simulate` is given (the CLI passes player/simulate_seat.h), the grips'
// simulated response is drawn too: a ring where each actuator actually is,
// lagging and overshooting the target dot as a Falcon with a hand on it
// does, and a tick on the Y gauge. The video is re-encoded as H.264 MP4 (datasets/video_writer.h: written under a
// temporary name, renamed when complete).

#include <functional>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

struct PreviewOptions {
  std::string video;             // input film
  std::string track;             // *.haptic.csv (default: <video stem>.haptic.csv)
  // A motion platform track (*.platform.csv) to draw instead of the HapSeat's
  // actuators: a seat that moves (datasets/preview_platform.h).
  std::string platform_track;
  // With platform_track: also draw where a simulated platform is
  // (platform/sim_platform.h: drives with lag and overshoot).
  bool simulate_platform = false;
  std::string output;            // output .mp4
  // The camera path giving the burnt-in shot and camera model and, when the
  // track has no effect column, the classifier's effects. Default: <video
  // stem>.camera.csv beside the video when it exists (else those lines are left out).
  std::string camera;
  bool burn_in = true;           // timecode, shot, camera model, effect label
  bool audio = true;             // keep the film's sound (none: a silent preview)
  // Only this range of the film: seconds ("62.5") or a timecode
  // ("00:01:02:12", frames at the film's rate); empty: the start / the end.
  // The sound is cut to the same frames. A range outside the film, or
  // from >= to, is a UsageError.
  std::string from, to;
  int max_side = 1280;           // longest side of the output, pixels (0: as decoded)
  double inset_fraction = 0.45;  // inset width as a fraction of the frame width
  double trail_s = 1.0;          // length of the trail
  int crf = 20;                  // x264 quality
  // Optional: the seat's response to the track (where the grips are).
  std::function<HapticTrack(const HapticTrack& targets)> simulate;
  void Check() const;  // throws UsageError
};

// Renders; `progress(done, total_estimate)` is called every few frames
// (frames decoded, including those before `from`, of those up to `to`).
// Returns the number of frames written. Throws hapcine::Error naming the
// file on bad input; never leaves a partial output.
int RenderPreview(const PreviewOptions& options,
                  const std::function<void(int, int)>& progress = {});

}  // namespace hapcine
