// TrackCameraEstimator's occlusion-order votes (occlusion_order.h): the
// window's buffered frames give the events, each candidate's cameras the
// depths. Kept apart from track_estimator_window.cc: one hook in ProcessWindow.

#include <cstdlib>
#include <iostream>

#include "estimate/track_estimator.h"

namespace hapcine {

std::vector<OcclusionVotes> TrackCameraEstimator::OcclusionVotesOf(
    const std::vector<const std::vector<BaCamera>*>& candidates) const {
  const int n = static_cast<int>(keyframes_.size());
  std::vector<OcclusionVotes> votes(candidates.size());
  if (n < 2) return votes;
  // Every frame of the window (not only keyframes: a track ends between
  // them), each with the last keyframe at or before it as depth reference.
  std::vector<const std::map<long, Eigen::Vector2d>*> frames;
  std::vector<int> frame_keyframe;
  int k = 0;
  for (int pos = keyframes_.front().pos; pos <= keyframes_.back().pos; ++pos) {
    while (k + 1 < n && keyframes_[k + 1].pos <= pos) ++k;
    frames.push_back(&At(pos).u);
    frame_keyframe.push_back(k);
  }
  const OcclusionOptions opt;
  const std::vector<OcclusionEvent> events =
      FindOcclusionEvents(frames, frame_keyframe, Eigen::Vector2d(0.5, 0.5 * height_ / width_), opt);
  std::map<long, KeyframeTrack> tracks;
  for (int i = 0; i < n; ++i)
    for (const auto& [id, u] : At(keyframes_[i].pos).u) tracks[id].push_back({i, u});
  for (size_t c = 0; c < candidates.size(); ++c) votes[c] = CountOcclusionVotes(*candidates[c], tracks, events, opt);
  // Diagnostic (docs/estimate.md): events and agree/disagree per candidate.
  if (std::getenv("HAPCINE_OCCLUSION_DEBUG")) {
    std::cerr << "occlusion frame " << At(keyframes_.front().pos).tracks.index << " events " << events.size();
    for (size_t c = 0; c < votes.size(); ++c)
      std::cerr << "  " << votes[c].agree << "/" << votes[c].disagree << " (z "
                << candidates[c]->back().center.z() - candidates[c]->front().center.z() << ", f ratio "
                << std::exp(candidates[c]->back().log_focal - candidates[c]->front().log_focal) << ")";
    std::cerr << "\n";
  }
  return votes;
}

}  // namespace hapcine
