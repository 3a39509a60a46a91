#pragma once
// The project's standard figures, built as Figure descriptions (plot_figure.h)
// and rendered by svg_writer.h / plot_png.h:
//  - a camera path (optionally with an estimate overlaid): pan/tilt/roll,
//    camera centre x/y/z and horizontal FOV over time;
//  - a haptic track: head / left hand / right hand displacement x/y/z over
//    time (the paper's Figure 4), and the `effect` column as labelled bands.

#include <string>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "datasets/plot_figure.h"

namespace hapcine {

struct CameraPlotOptions {
  // Re-express each path relative to its own first frame (R_0^-1 R_t and
  // R_0^-1 (c_t - c_0)), so a ground truth in any world frame and an estimate
  // that starts at the origin overlay directly.
  bool relative_to_first = true;
  // Scale the estimate's positions by the least-squares factor onto the
  // ground truth (monocular estimates have no metric scale). Needs `relative_to_first`.
  bool scale_estimate = true;
  std::string title;
  void Check() const;  // throws UsageError
};

// `est` may be null. The estimate is drawn dashed in the same colours.
Figure CameraPathFigure(const CameraPath& gt, const CameraPath* est,
                        const CameraPlotOptions& options = {});

// Positions in millimetres; effect bands on a time line under the panels
// when any sample has an `effect`.
Figure HapticTrackFigure(const HapticTrack& track, const std::string& title = "");

}  // namespace hapcine
