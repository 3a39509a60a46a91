#pragma once
// Filtering a frame's tracks held as parallel arrays (positions, ids), as
// the tracker and the descriptor re-linker do after each check.

#include <opencv2/core.hpp>
#include <vector>

namespace hapcine {

// Keeps the tracks i for which keep(i) holds, in their order; keep(i) is
// called once per track, in increasing i, before any of them moves.
template <typename Keep>
void KeepTracksIf(std::vector<cv::Point2f>* points, std::vector<long>* ids, Keep keep) {
  size_t kept = 0;
  for (size_t i = 0; i < points->size(); ++i) {
    if (!keep(i)) continue;
    (*points)[kept] = (*points)[i];
    (*ids)[kept] = (*ids)[i];
    ++kept;
  }
  points->resize(kept);
  ids->resize(kept);
}

}  // namespace hapcine
