#include "datasets/shot_boundaries.h"

#include <cstdlib>

namespace hapcine {

ShotBoundaryScore ScoreShotBoundaries(const std::vector<ShotSample>& samples,
                                      int tolerance_frames) {
  ShotBoundaryScore s;
  s.tolerance_frames = tolerance_frames;
  for (size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].gt_shot != samples[i - 1].gt_shot) s.gt_boundaries.push_back(samples[i].frame);
    if (samples[i].est_shot != samples[i - 1].est_shot)
      s.est_boundaries.push_back(samples[i].frame);
  }
  // Both lists are sorted and every window has the same width, so matching
  // greedily from the left finds the largest one-to-one matching: pair the
  // two earliest when they are close enough, else drop the earlier one (it
  // cannot match anything later either).
  size_t g = 0, e = 0;
  while (g < s.gt_boundaries.size() && e < s.est_boundaries.size()) {
    const int a = s.gt_boundaries[g], b = s.est_boundaries[e];
    if (std::abs(a - b) <= tolerance_frames) {
      ++s.matched;
      ++g;
      ++e;
    } else if (a < b) {
      ++g;
    } else {
      ++e;
    }
  }
  if (!s.est_boundaries.empty())
    s.precision = static_cast<double>(s.matched) / s.est_boundaries.size();
  if (!s.gt_boundaries.empty())
    s.recall = static_cast<double>(s.matched) / s.gt_boundaries.size();
  return s;
}

}  // namespace hapcine
