#pragma once
// A window's 3-D points for the bundle adjustment: which tracks
// (point_selection.h) and where they start.

#include <Eigen/Core>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

using KeyframeTracks = std::map<long, Eigen::Vector2d>;  // track id -> normalised coordinates

struct WindowTracks {
  std::map<long, std::vector<int>> seen;    // track id -> the keyframes that see it, in order
  std::vector<std::pair<int, long>> order;  // point k is the track order[k].second (first: -keyframes seen)
  std::map<long, int> point_of_track;       // track id -> point index
};

// The tracks seen by >= 2 of the window's keyframes (`keyframes[i]`: the
// tracks of keyframe i), not in `outliers`: up to `max_points` of them, taken
// in turns from grid_cells x grid_cells image cells, longest first in each
// (grid_cells <= 1: simply the longest).
WindowTracks SelectWindowPoints(const std::vector<const KeyframeTracks*>& keyframes,
                                const std::set<long>& outliers, int max_points, int grid_cells);

// Each point anchored at the first keyframe that sees it (on its ray from
// `cams`' poses), with one observation per keyframe that sees it. With
// depth: inverse depth by midpoint triangulation with the observing keyframe
// farthest from the anchor, `fallback_rho` where that fails (no baseline,
// behind the camera); without: rho = 0 (bearings). Reads only: two threads
// may call it at once.
void InitWindowPoints(const std::vector<BaCamera>& cams, const WindowTracks& tracks,
                      const std::vector<const KeyframeTracks*>& keyframes, bool with_depth,
                      double fallback_rho, std::vector<BaPoint>* points, std::vector<BaObservation>* obs);

}  // namespace hapcine
