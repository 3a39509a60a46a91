#pragma once
// Shot-boundary agreement between two camera paths' `shot` columns
// (docs/eval.md "Shot boundaries"): a boundary is a matched frame whose shot
// differs from the previous matched frame's. An estimated boundary counts as
// found when it lies within `tolerance_frames` of a ground-truth one (each
// boundary used once; a fade may be reported a few frames from where the
// ground truth puts it). precision = matched / estimated boundaries, recall =
// matched / ground-truth boundaries, n/a when the denominator is 0.

#include <optional>
#include <vector>

namespace hapcine {

struct ShotSample {
  int frame = 0;  // ground-truth frame index of a matched frame
  int gt_shot = 0;
  int est_shot = 0;
};

struct ShotBoundaryScore {
  int tolerance_frames = 0;
  std::vector<int> gt_boundaries;   // first frames of the ground truth's shots after the first
  std::vector<int> est_boundaries;  // the same for the estimate
  int matched = 0;
  std::optional<double> precision;  // n/a without estimated boundaries
  std::optional<double> recall;     // n/a without ground-truth boundaries
};

// `samples` in increasing frame order.
ShotBoundaryScore ScoreShotBoundaries(const std::vector<ShotSample>& samples,
                                      int tolerance_frames);

}  // namespace hapcine
