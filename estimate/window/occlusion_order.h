#pragma once
// Occlusion order: which branch of the axial dolly/zoom ambiguity is real.
//
// Along the optical axis the tracks fit a forward dolly zooming out and a
// backward move at about constant focal equally well (axial_ambiguity.h):
// the mirrored branch re-arranges the inverse depths affinely with a negative
// slope, w' = alpha + beta w (beta < 0), so the subject lands behind the
// background. Reprojection error cannot tell them apart; occlusion can. A
// track that ends (or starts) in the middle of the image, next to tracks that
// live on, was most often covered (or uncovered) by a nearer surface: the
// subject's silhouette passing over the background. Such a track must be
// deeper than the nearest of its surviving neighbours. On real footage that
// holds whatever the scene: what covers is in front of what is covered.
//
// Per event the test is affine-equivariant: with w the inverse depths of the
// surviving neighbours, the event agrees when the ending track's w lies in
// the far half of [min w, max w] (an occluder is much nearer than the covered
// track, nothing is much farther). Under w' = alpha + beta w with beta < 0 the
// far and near halves swap, so the mirrored branch sees exactly the opposite
// votes: the count separates the branches, and other causes of track ends
// (tracking failure, low texture: neighbours at the same depth, no contrast;
// image border: skipped) add votes to neither side systematically.

#include <Eigen/Core>
#include <map>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

struct OcclusionOptions {
  // Events closer than this to the image border (normalised units, fraction
  // of the width) are the frame's edge, not an occlusion.
  double border = 0.04;
  double radius = 0.05;   // survivors within this distance are the neighbours
  int min_neighbours = 3;
  // The neighbours' inverse-depth spread must be at least this fraction of
  // the window's (2nd..98th percentile of all event tracks): a depth edge.
  double min_spread = 0.25;
  // |position of the ending track in [min w, max w] - 1/2| must exceed this:
  // ending tracks in the middle of their neighbours' depths vote for nothing.
  double min_margin = 0.2;
  // Count tracks that begin next to survivors too (uncovered background).
  // Off: the detector starts new tracks wherever it finds room, and the
  // silhouette's own corners (T-junctions, fresh texture on the subject) start
  // there in either direction of motion; on a dolly zoom the births voted
  // 6/15 against the branch the ends voted for 115/38.
  bool births = false;
};

// A track that ends (or begins) inside the image among tracks that live on.
struct OcclusionEvent {
  long track = 0;
  int keyframe = 0;              // reference keyframe for depths (the last one at or before the event)
  std::vector<long> neighbours;  // alive before and after the event, within `radius`
  bool birth = false;            // the track begins here (uncovered) rather than ends (covered)
};

// frames: each frame's tracks (normalised coordinates by track id), in order;
// frame_keyframe: for each frame, the index of its reference keyframe.
// half_extent: half the image size in normalised units (0.5, 0.5 h / w).
std::vector<OcclusionEvent> FindOcclusionEvents(const std::vector<const std::map<long, Eigen::Vector2d>*>& frames,
                                                const std::vector<int>& frame_keyframe,
                                                const Eigen::Vector2d& half_extent,
                                                const OcclusionOptions& options = {});

// Observations of one track at keyframes (normalised coordinates).
using KeyframeTrack = std::vector<std::pair<int, Eigen::Vector2d>>;

// Inverse depth of a track in camera `reference`, by midpoint triangulation
// between the two observing cameras farthest apart; signed (negative: beyond
// infinity); NaN when it cannot be triangulated.
double TrackInverseDepth(const std::vector<BaCamera>& cams, const KeyframeTrack& track, int reference);

struct OcclusionVotes {
  int agree = 0;     // ending track deeper than its nearest neighbours
  int disagree = 0;  // ending track nearer than its farthest neighbours
  // Sign-test statistic (agree - disagree) / sqrt(agree + disagree); 0 if none.
  double Z() const;
};

// Votes of the reconstruction `cams` on the events; tracks without keyframe
// observations (or not triangulable) are skipped.
OcclusionVotes CountOcclusionVotes(const std::vector<BaCamera>& cams, const std::map<long, KeyframeTrack>& tracks,
                                   const std::vector<OcclusionEvent>& events, const OcclusionOptions& options = {});

// The candidates (reconstructions of one window) the occlusion order rules
// out: those whose votes contradict it (Z <= -min_z), and only when another
// candidate is supported (Z >= min_z); otherwise none (no evidence).
std::vector<char> ContradictedByOcclusion(const std::vector<OcclusionVotes>& votes, double min_z = 2.0);

}  // namespace hapcine
