#include "estimate/window/depth_layers.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"

namespace hapcine {

std::vector<int> JudgeDepthLayers(const std::vector<DepthSample>& frame, const DepthLayerOptions& options) {
  std::vector<int> verdict(frame.size(), -1);
  if (frame.size() < 3) return verdict;
  std::vector<double> all;
  all.reserve(frame.size());
  for (const DepthSample& s : frame) all.push_back(s.w);
  const double frame_spread = Quantile(all, 0.98) - Quantile(all, 0.02);
  if (!(frame_spread > 0)) return verdict;
  const double r2 = options.radius * options.radius;
  std::vector<double> nb;
  for (size_t i = 0; i < frame.size(); ++i) {
    nb.clear();
    for (size_t j = 0; j < frame.size(); ++j)
      if (j != i && (frame[j].u - frame[i].u).squaredNorm() <= r2) nb.push_back(frame[j].w);
    if (static_cast<int>(nb.size()) < options.min_neighbours) continue;
    const auto [lo, hi] = std::minmax_element(nb.begin(), nb.end());
    const double spread = *hi - *lo;
    if (spread < options.min_spread * frame_spread) continue;  // no depth edge here
    const double w = frame[i].w, pos = (w - *lo) / spread;
    int support = 0;
    for (double v : nb) support += std::abs(v - w) <= options.support * spread;
    verdict[i] = pos > options.margin && pos < 1 - options.margin && support < options.min_support;
  }
  return verdict;
}

std::set<long> TracksBetweenDepthLayers(const std::vector<std::vector<DepthSample>>& frames,
                                        const DepthLayerOptions& options) {
  std::map<long, std::pair<int, int>> tally;  // track -> (judged, flagged)
  for (const auto& frame : frames) {
    const std::vector<int> v = JudgeDepthLayers(frame, options);
    for (size_t i = 0; i < frame.size(); ++i) {
      if (v[i] < 0) continue;
      auto& t = tally[frame[i].track];
      ++t.first;
      t.second += v[i];
    }
  }
  std::set<long> out;
  for (const auto& [id, t] : tally)
    if (t.second > 0 && t.second >= options.min_flagged_fraction * t.first) out.insert(id);
  return out;
}

std::set<long> TracksBetweenDepthLayers(const std::vector<BaCamera>& cams,
                                        const std::map<long, KeyframeTrack>& tracks,
                                        const DepthLayerOptions& options) {
  const int n = static_cast<int>(cams.size());
  std::vector<std::vector<DepthSample>> frames(n);
  for (const auto& [id, track] : tracks) {
    if (track.size() < 2) continue;
    for (const auto& [k, u] : track) {
      if (k < 0 || k >= n) continue;
      const double w = TrackInverseDepth(cams, track, k);
      if (std::isfinite(w)) frames[k].push_back({id, u, w});
    }
  }
  return TracksBetweenDepthLayers(frames, options);
}

}  // namespace hapcine
