#pragma once
// Depth-layer cue: tracks whose depth lies in the gap between two depth
// layers of their neighbourhood (occlusion-edge corners).
//
// A corner formed by a foreground silhouette over background texture (a
// T-junction) slides along the silhouette; under a camera translating in one
// direction it fits a rigid point well enough (its reprojection RMS stays
// small) but at a depth that belongs to neither surface: between the
// foreground and the background that meet there. A rigid point lies on a
// surface, so some of its neighbours share its depth: on a slanted surface
// (a floor) the neighbours' depths spread continuously and the point has
// support; at a depth edge it sits with one of the two layers. The cue: in a
// neighbourhood whose inverse depths span a depth edge, a track whose inverse
// depth is well inside [min w, max w] and that no neighbour shares (within a
// fraction of the neighbours' spread) is between the layers. Affine in w, so
// a global scale or offset of the reconstruction does not change it.
//
// Judged at several reference frames (keyframes); a track is flagged when
// most of the frames that could judge it flag it.

#include <Eigen/Core>
#include <map>
#include <set>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/window/occlusion_order.h"

namespace hapcine {

struct DepthLayerOptions {
  double radius = 0.05;       // neighbours within this distance (normalised units, fraction of the width)
  int min_neighbours = 4;     // fewer: not judged
  // The neighbours' inverse-depth spread must be at least this fraction of
  // the frame's (2nd..98th percentile): a depth edge, not a smooth surface.
  double min_spread = 0.25;
  // The track must lie at least this far (fraction of the neighbours' spread)
  // from both ends of [min w, max w]: strictly between the layers.
  double margin = 0.2;
  // A neighbour within this fraction of the spread supports the track's depth.
  double support = 0.1;
  int min_support = 1;        // fewer supporting neighbours: unsupported
  double min_flagged_fraction = 0.5;  // of the reference frames that judged the track
};

// One track in one reference frame: image position and inverse depth.
struct DepthSample {
  long track = 0;
  Eigen::Vector2d u = Eigen::Vector2d::Zero();  // normalised coordinates
  double w = 0;                                 // inverse depth in that frame
};

// Per sample of one frame: -1 not judged, 0 rigid-looking, 1 between layers.
std::vector<int> JudgeDepthLayers(const std::vector<DepthSample>& frame, const DepthLayerOptions& options = {});

// Tracks flagged over several reference frames (each a set of samples).
std::set<long> TracksBetweenDepthLayers(const std::vector<std::vector<DepthSample>>& frames,
                                        const DepthLayerOptions& options = {});

// The same from a reconstruction: each keyframe of `cams` is a reference
// frame; every track with >= 2 keyframe observations is triangulated
// (TrackInverseDepth) in it.
std::set<long> TracksBetweenDepthLayers(const std::vector<BaCamera>& cams,
                                        const std::map<long, KeyframeTrack>& tracks,
                                        const DepthLayerOptions& options = {});

}  // namespace hapcine
