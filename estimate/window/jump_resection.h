#pragma once
// A keyframe the tracker reached by a jump (FrameTracks::jump: linked by
// descriptors beyond KLT's reach) starts from the two-view pose of its link,
// solved from the few tracks that link shares with the keyframe before it.
// Where the jump frame continues tracks that earlier keyframes triangulate,
// its pose is measured better by resection against those points (as
// incremental structure from motion places a new view); the keyframes after
// it, chained from it, move with it.

#include <optional>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/window/window_points.h"

namespace hapcine {

// The pose of keyframe `i` (focal: its own) from the tracks it shares with
// points that keyframes 0..i-1 (`cams`, `tracks`) triangulate with a
// parallax of at least 1 degree: RANSAC PnP (2 px at the reference width),
// then at least `min_inliers` inliers. Nothing where too few points exist.
std::optional<BaCamera> ResectKeyframe(const std::vector<BaCamera>& cams,
                                       const std::vector<const KeyframeTracks*>& tracks, int i,
                                       int min_inliers = 8);

// Keyframes i.. moved rigidly so that keyframe i takes `placed`'s pose
// (rotation and centre; focals and the chain's scale unchanged).
void MoveChainFrom(int i, const BaCamera& placed, std::vector<BaCamera>* cams);

}  // namespace hapcine
