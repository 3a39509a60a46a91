#pragma once
// The camera path's per-shot quality header lines (docs/formats.md,
// `# shot_quality.<shot>=first:F last:L frames:N lost:K ...`): the one
// writer and reader of their text. The estimator fills them
// (estimate/shot_quality.h: the summary and the doubtful rule); `hapcine
// estimate`, `make` and `batch` read them back.

#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.h"

namespace hapcine {

struct ShotQuality {
  int shot = 0;
  int first_frame = 0, last_frame = 0;  // frame indices
  int frames = 0;                       // rows of the shot
  int lost = 0;                         // of them, model `lost`
  double median_confidence = 0;         // over all its frames (lost ones count 0)
  // From the shot's bundle-adjustment windows (none with --backend colmap):
  std::optional<double> inlier_ratio;      // two-view inliers / correspondences of its keyframes
  std::optional<double> rms_px;            // reprojection RMS, pixels at 960 px width
  std::optional<bool> focal_observable;    // some window turned enough to calibrate the focal
  // Frames written by windows whose zoom decision was ambiguous
  // (zoom_evidence.h: the evidence within half a threshold of the other
  // reading; the confidence lowered, the reading without zoom taken where it
  // is the simpler one); 0: no ambiguous decision, or none to make.
  std::optional<int> zoom_ambiguous;
  // Of those frames, the ones whose window kept the zoom (the rest: the
  // reading without zoom, a dolly or a fixed lens). Written only where
  // zoom_ambiguous is above 0; unknown in headers written before it.
  std::optional<int> ambiguous_zoom_kept;
  // The median, over its keyframe intervals, of the share of the frame's
  // edge cells holding the camera motion's inliers (1 for an interval read
  // as still; estimate/geometry/border_support.h). Below one half: the
  // motion rests on a region inside the picture, no background confirms it.
  // Unknown without windows and in headers written before it.
  std::optional<double> border_support;
  // The border stayed still where the shot's motion would have moved it
  // (estimate/geometry/border_support.h, StillBorderAroundMotion): read as
  // a subject moving before a still camera, every frame of the shot held at
  // its first pose.
  bool still_border = false;
  bool doubtful = false;
};

// `# shot_quality.<shot>=first:F last:L frames:N lost:K median_confidence:C
// inlier_ratio:I rms_px:R focal_observable:0|1 zoom_ambiguous:Z
// ambiguous_zoom_kept:K border_support:B still_border:1 doubtful:0|1` (I, R,
// focal, Z, B absent when unknown; K only where Z is above 0; still_border
// only where set) into the path's metadata.
void WriteShotQuality(const std::vector<ShotQuality>& shots, CameraPath* path);

// The reverse, ordered by shot. A hand-edited value that is not what the
// writer writes (a frame index or count that is negative, fractional or
// beyond int, a non-finite number, a flag other than 0 or 1, trailing
// text) is ignored: the field keeps its default, as when it is absent (an
// older header without `zoom_ambiguous`). A key whose shot is not an int
// is not a shot line. Unknown names are ignored.
std::vector<ShotQuality> ReadShotQuality(const CameraPath& path);

// The same from a camera path file's header lines alone (the rows are not
// read): empty when the file cannot be read or its header has no summary.
std::vector<ShotQuality> ReadShotQualityOfFile(const std::string& camera_csv);

// What `hapcine make` and the batch summary report of a film's shots.
struct ShotQualityCounts {
  int shots = 0;
  int doubtful = 0;        // shots flagged doubtful
  int zoom_ambiguous = 0;  // shots with some frame of an ambiguous zoom decision
  int lost_frames = 0;     // summed over the shots, capped at the int maximum
};
ShotQualityCounts CountShotQuality(const std::vector<ShotQuality>& shots);

}  // namespace hapcine
