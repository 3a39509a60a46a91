#include "estimate/window/occlusion_order.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hapcine {

std::vector<OcclusionEvent> FindOcclusionEvents(const std::vector<const std::map<long, Eigen::Vector2d>*>& frames,
                                                const std::vector<int>& frame_keyframe,
                                                const Eigen::Vector2d& half_extent,
                                                const OcclusionOptions& options) {
  const int n = static_cast<int>(std::min(frames.size(), frame_keyframe.size()));
  // First and last frame of each track in the list (a re-linked track that
  // skips frames is one track, not an end and a start).
  std::map<long, std::pair<int, int>> life;
  for (int i = 0; i < n; ++i)
    for (const auto& [id, u] : *frames[i]) {
      auto it = life.find(id);
      if (it == life.end()) life[id] = {i, i};
      else it->second.second = i;
    }
  const double r2 = options.radius * options.radius;
  std::vector<OcclusionEvent> events;
  auto add = [&](long id, int at, int other) {
    // The track is seen in frame `at`, not in the adjacent frame `other`.
    const Eigen::Vector2d u = frames[at]->at(id);
    if (std::abs(u.x()) > half_extent.x() - options.border || std::abs(u.y()) > half_extent.y() - options.border)
      return;
    OcclusionEvent e;
    e.track = id;
    e.keyframe = frame_keyframe[std::min(at, other)];
    e.birth = other < at;
    for (const auto& [nid, v] : *frames[at])
      if (nid != id && (v - u).squaredNorm() <= r2 && frames[other]->count(nid)) e.neighbours.push_back(nid);
    if (static_cast<int>(e.neighbours.size()) >= options.min_neighbours) events.push_back(std::move(e));
  };
  for (const auto& [id, span] : life) {
    // An empty next frame is a tracking loss (blank, cut), not an occlusion.
    if (span.second + 1 < n && !frames[span.second + 1]->empty()) add(id, span.second, span.second + 1);
    if (options.births && span.first > 0 && !frames[span.first - 1]->empty()) add(id, span.first, span.first - 1);
  }
  return events;
}

double TrackInverseDepth(const std::vector<BaCamera>& cams, const KeyframeTrack& track, int reference) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int nc = static_cast<int>(cams.size());
  if (track.size() < 2 || reference < 0 || reference >= nc) return nan;
  auto ray = [&](const std::pair<int, Eigen::Vector2d>& o) {
    const BaCamera& c = cams[o.first];
    const double f = std::exp(c.log_focal);
    return (c.world_from_cam * Eigen::Vector3d(o.second.x() / f, o.second.y() / f, 1)).normalized().eval();
  };
  const auto& first = track.front();
  if (first.first < 0 || first.first >= nc) return nan;
  const BaCamera& ca = cams[first.first];
  int best = -1;
  double best_base = 0;
  for (size_t j = 1; j < track.size(); ++j) {
    if (track[j].first < 0 || track[j].first >= nc) continue;
    const double base = (cams[track[j].first].center - ca.center).norm();
    if (base > best_base) {
      best_base = base;
      best = static_cast<int>(j);
    }
  }
  if (best < 0) return nan;
  const Eigen::Vector3d ra = ray(first), rb = ray(track[best]);
  const Eigen::Vector3d w = cams[track[best].first].center - ca.center;
  const double bb = ra.dot(rb), d1 = ra.dot(w), d2 = rb.dot(w);
  const double den = 1 - bb * bb, num = d1 - bb * d2;  // distance along ra: num / den
  if (std::abs(num) < 1e-12) return nan;                 // at the camera
  // Homogeneous point (ra + inv * ca, inv): finite through infinity, and a
  // point "beyond infinity" (the wrong branch's subject) gets inv < 0.
  const double inv = den / num;
  const BaCamera& cr = cams[reference];
  const double z = (cr.world_from_cam.conjugate() * (ra + inv * (ca.center - cr.center))).z();
  if (!(z > 1e-9)) return nan;
  const double out = inv / z;
  return std::isfinite(out) ? out : nan;
}

double OcclusionVotes::Z() const {
  const int n = agree + disagree;
  return n > 0 ? (agree - disagree) / std::sqrt(static_cast<double>(n)) : 0.0;
}

OcclusionVotes CountOcclusionVotes(const std::vector<BaCamera>& cams, const std::map<long, KeyframeTrack>& tracks,
                                   const std::vector<OcclusionEvent>& events, const OcclusionOptions& options) {
  OcclusionVotes votes;
  auto depth = [&](long id, int reference) {
    auto it = tracks.find(id);
    return it == tracks.end() ? std::numeric_limits<double>::quiet_NaN()
                              : TrackInverseDepth(cams, it->second, reference);
  };
  // Per event: the ending track's and its neighbours' inverse depths.
  struct Depths {
    double w;
    std::vector<double> nb;
  };
  std::vector<Depths> all;
  std::vector<double> pool;
  for (const auto& e : events) {
    Depths d{depth(e.track, e.keyframe), {}};
    if (!std::isfinite(d.w)) continue;
    for (long id : e.neighbours) {
      const double v = depth(id, e.keyframe);
      if (std::isfinite(v)) d.nb.push_back(v);
    }
    if (static_cast<int>(d.nb.size()) < options.min_neighbours) continue;
    pool.push_back(d.w);
    pool.insert(pool.end(), d.nb.begin(), d.nb.end());
    all.push_back(std::move(d));
  }
  if (all.empty()) return votes;
  // The inverse-depth spread of the event tracks (2nd..98th percentile: the
  // subject may be a small share of them): the unit of a depth edge, the
  // same under any affine re-arrangement of the depths.
  std::sort(pool.begin(), pool.end());
  const double spread = pool[pool.size() * 49 / 50] - pool[pool.size() / 50];
  if (!(spread > 0)) return votes;
  for (const auto& d : all) {
    const auto [lo, hi] = std::minmax_element(d.nb.begin(), d.nb.end());
    const double range = *hi - *lo;
    if (!(range >= options.min_spread * spread)) continue;  // no depth edge here
    const double t = (d.w - *lo) / range;  // 0: as far as the farthest neighbour, 1: as near as the nearest
    if (t < 0.5 - options.min_margin) ++votes.agree;
    else if (t > 0.5 + options.min_margin) ++votes.disagree;
  }
  return votes;
}

std::vector<char> ContradictedByOcclusion(const std::vector<OcclusionVotes>& votes, double min_z) {
  std::vector<char> out(votes.size(), 0);
  bool supported = false;
  for (const auto& v : votes) supported |= v.Z() >= min_z;
  if (!supported) return out;
  for (size_t i = 0; i < votes.size(); ++i) out[i] = votes[i].Z() <= -min_z;
  return out;
}

}  // namespace hapcine
