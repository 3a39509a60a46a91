// TrackCameraEstimator's depth-layer cue (depth_layers.h): the window's
// keyframe observations, depths from a candidate reconstruction. Kept apart
// from track_estimator_window.cc: one hook in ProcessWindow's whole-track rejection.

#include "estimate/depth_layers.h"
#include "estimate/track_estimator.h"

namespace hapcine {

std::set<long> TrackCameraEstimator::TracksBetweenLayersOf(const std::vector<BaCamera>& cams,
                                                           const std::set<long>& excluded) const {
  std::map<long, KeyframeTrack> tracks;
  const int n = static_cast<int>(std::min(keyframes_.size(), cams.size()));
  for (int i = 0; i < n; ++i)
    for (const auto& [id, u] : At(keyframes_[i].pos).u)
      if (!excluded.count(id) && !outlier_tracks_.count(id)) tracks[id].push_back({i, u});
  return TracksBetweenDepthLayers(cams, tracks);
}

}  // namespace hapcine
