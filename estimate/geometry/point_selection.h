#pragma once
// Which tracks a bundle-adjustment window turns into 3-D points.
//
// Longest-first alone favours occlusion-edge tracks: a corner formed by the
// subject's silhouette against the background slides smoothly, passes every
// check and stays in view longest, so on an orbit about half of the longest
// tracks are such corners, clustered on the subject's outline
// (docs/estimate.md, "Where the rotation error comes from"). Spreading the
// points over an image grid (round robin over the cells, longest first within
// a cell) lets the textured background, where most tracks are rigid, have its
// share.

#include <Eigen/Core>
#include <vector>

namespace hapcine {

struct TrackCandidate {
  long id = 0;
  int length = 0;        // keyframes that see the track
  Eigen::Vector2d u{0, 0};  // where it is seen (any common image coordinates)
};

// Up to `max_points` candidate ids. grid_cells <= 1: the longest tracks
// (ties by id). Otherwise the candidates' bounding box is cut into
// grid_cells x grid_cells cells and the cells take turns: every cell's longest
// track, then every cell's second longest, ... (within a turn, longest
// first, so a cap that falls inside a turn keeps the longer tracks).
std::vector<long> SelectWindowTracks(std::vector<TrackCandidate> candidates, int max_points, int grid_cells);

}  // namespace hapcine
