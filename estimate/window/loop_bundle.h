#pragma once
// A shot's keyframes adjusted together after its windows, where tracks
// close a loop the windows could not see: a track observed by keyframes of
// two windows, absent in between (an orbit that came round and re-linked
// the points of its earlier turn: the tracker's revisit links). Each window
// saw one stretch of such a track as a point of its own, so the drift the
// windows accumulated between the two stretches went unmeasured; one
// bundle adjustment over all the keyframes, with the windows' solutions as
// its start, makes both stretches one point and spreads the loop's
// disagreement where the observations put it (docs/estimate.md "Loop
// bundle").

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/window/window_points.h"

namespace hapcine {

struct LoopKeyframe {
  int frame = 0;         // frame index
  BaCamera cam;          // as its window solved it (the shot's units)
  KeyframeTracks u;      // its tracks, normalised coordinates
  int first_window = 0;  // the windows that solved it (an overlap keyframe: two)
  int last_window = 0;
};

struct LoopBundleOptions {
  int min_loop_tracks = 12;  // fewer loop tracks: nothing is adjusted (the estimator's minimum)
  int max_points = 600;      // points of the adjustment (longest first, over a grid)
  int point_grid_cells = 6;
  double track_rms_cut = 0.2 / kReferenceWidthPx;  // whole-track cut floor, normalised units
  int ba_iterations = 40;
  int num_threads = 1;
};

struct LoopBundleResult {
  bool adjusted = false;            // the cameras were replaced
  int loop_tracks = 0;              // tracks seen by keyframes of windows that share no keyframe
  int points = 0, points_kept = 0;  // points adjusted, and left after the whole-track cut
  int observations = 0;
  double rms_before_px = 0, rms_after_px = 0;  // at 960 px width
  std::vector<BaCamera> cameras;               // per keyframe (the input's where not adjusted)
};

// Tracks seen by two keyframes no window shares, with none of the keyframes
// between seeing them: each window had one stretch only.
int CountLoopTracks(const std::vector<LoopKeyframe>& keyframes);

// With at least min_loop_tracks loop tracks: every keyframe's rotation and
// centre adjusted (the first two held: the gauge and the scale, as the
// shot's first window held them; focals held as the windows solved them)
// against the longest tracks and every loop track, with the windows' robust
// rounds (observation cut, whole-track cut). `outliers`: tracks never used.
// `with_depth`: the shot translates (otherwise bearings; centres held).
LoopBundleResult AdjustLoop(const std::vector<LoopKeyframe>& keyframes,
                            const std::set<long>& outliers, bool with_depth,
                            const LoopBundleOptions& options);

}  // namespace hapcine
