#pragma once
// The project's standard figures, built as Figure descriptions (plot_figure.h)
// and rendered by svg_writer.h / plot_png.h:
//  - a camera path (optionally with an estimate overlaid): pan/tilt/roll,
//    camera centre x/y/z and horizontal FOV over time;
//    and the effects the classifier finds in each path (haptics/
//    effect_classifier.h) as labelled bands on a time line;
//  - haptic tracks: head / left hand / right hand displacement x/y/z over
//    time, several tracks overlaid like the paper's Figure 4 (cinematic vs
//    semantic for the Zoom-in clip), and each track's `effect` column as
//    labelled bands.

#include <map>
#include <optional>
#include <string>
#include <vector>

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
  // A time line of the classifier's effect labels under the curves, one row
  // per path (GT, est).
  bool effect_labels = true;
  // Shot boundaries (the `shot` column) as cut lines, and the `confidence`
  // column (the estimate's, else the first path's) as a shaded panel under
  // the curves, when the paths have them.
  bool cuts = true;
  bool confidence = true;
  std::string title;
  void Check() const;  // throws UsageError
};

// `est` may be null. The estimate is drawn dashed in the same colours.
Figure CameraPathFigure(const CameraPath& gt, const CameraPath* est,
                        const CameraPlotOptions& options = {});

// Positions in millimetres; effect bands on a time line under the panels
// when any sample has an `effect`; cut lines where the first track's `shot`
// column changes.
Figure HapticTrackFigure(const HapticTrack& track, const std::string& title = "");
// Several tracks on the same panels: the first solid, the others dashed,
// legend entries suffixed with `names` (default: each track's model); one
// effect time line per track that has an `effect` column.
Figure HapticTracksFigure(const std::vector<const HapticTrack*>& tracks,
                          const std::string& title = "",
                          const std::vector<std::string>& names = {});

// Shot boundaries: the times where the `shot` column changes (the first row of
// each new shot). Empty without the column.
std::vector<double> ShotCutTimes(const CameraPath& path);
std::vector<double> ShotCutTimes(const HapticTrack& track);
// The `confidence` column of a path as a shaded area over [0, 1] on a short
// panel (lost frames read 0); nullopt when no frame has the column.
std::optional<PlotPanel> ConfidencePanel(const CameraPath& path, const std::string& title);

// Labelled bands (one per run of equal label) on a band-only panel; runs
// labelled "none" are drawn light grey.
PlotPanel EffectTimeline(const std::string& title, const std::vector<double>& time_s,
                         const std::vector<std::string>& labels, double last_period_s,
                         std::map<std::string, int>* colors);

}  // namespace hapcine
