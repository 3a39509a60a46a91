#include "estimate/window/loop_bundle.h"

#include <algorithm>
#include <map>

#include "core/statistics.h"
#include "estimate/bundle/robust_bundle.h"

namespace hapcine {
namespace {

// Two keyframes share a window when their window ranges meet.
bool ShareAWindow(const LoopKeyframe& a, const LoopKeyframe& b) {
  return a.first_window <= b.last_window && b.first_window <= a.last_window;
}

// Per track, the keyframes that see it, in order.
std::map<long, std::vector<int>> SeenBy(const std::vector<LoopKeyframe>& keyframes) {
  std::map<long, std::vector<int>> seen;
  for (size_t k = 0; k < keyframes.size(); ++k)
    for (const auto& [id, u] : keyframes[k].u) seen[id].push_back(static_cast<int>(k));
  return seen;
}

// A gap in the track's keyframes (a keyframe between saw it not) whose two
// sides no window shares.
bool ClosesALoop(const std::vector<LoopKeyframe>& keyframes, const std::vector<int>& kfs) {
  for (size_t i = 1; i < kfs.size(); ++i)
    if (kfs[i] > kfs[i - 1] + 1 && !ShareAWindow(keyframes[kfs[i - 1]], keyframes[kfs[i]]))
      return true;
  return false;
}

std::vector<long> LoopTracks(const std::vector<LoopKeyframe>& keyframes) {
  std::vector<long> ids;
  for (const auto& [id, kfs] : SeenBy(keyframes))
    if (ClosesALoop(keyframes, kfs)) ids.push_back(id);
  return ids;
}

// The longest tracks over a grid (as a window picks them), and every loop
// track not among them: the loop is what the adjustment is for.
WindowTracks LoopPoints(const std::vector<const KeyframeTracks*>& tracks,
                        const std::set<long>& outliers, const std::vector<long>& loop,
                        const LoopBundleOptions& o) {
  WindowTracks w = SelectWindowPoints(tracks, outliers, o.max_points, o.point_grid_cells);
  for (long id : loop) {
    const auto it = w.seen.find(id);
    if (outliers.count(id) || it == w.seen.end() || w.point_of_track.count(id)) continue;
    w.point_of_track[id] = static_cast<int>(w.order.size());
    w.order.push_back({-static_cast<int>(it->second.size()), id});
  }
  return w;
}

// The upper median depth of the points in the first keyframe; 1 where none
// is in front.
double MedianDepth(const std::vector<LoopKeyframe>& keyframes, const std::vector<BaPoint>& points) {
  const BaCamera& cam = keyframes.front().cam;
  std::vector<double> z;
  for (const BaPoint& p : points) {
    if (!(p.homogeneous(3) > 1e-12)) continue;
    const Eigen::Vector3d x = p.anchor + p.Direction() / p.homogeneous(3);
    z.push_back((cam.world_from_cam.conjugate() * (x - cam.center)).z());
  }
  if (z.empty()) return 1;
  const double median = Quantile(z, 0.5);
  return median > 0 ? median : 1;
}

}  // namespace

int CountLoopTracks(const std::vector<LoopKeyframe>& keyframes) {
  return static_cast<int>(LoopTracks(keyframes).size());
}

LoopBundleResult AdjustLoop(const std::vector<LoopKeyframe>& keyframes,
                            const std::set<long>& outliers, bool with_depth,
                            const LoopBundleOptions& o) {
  LoopBundleResult r;
  for (const LoopKeyframe& k : keyframes) r.cameras.push_back(k.cam);
  const std::vector<long> loop = LoopTracks(keyframes);
  r.loop_tracks = static_cast<int>(loop.size());
  if (r.loop_tracks < o.min_loop_tracks || keyframes.size() < 3) return r;
  std::vector<const KeyframeTracks*> tracks;
  for (const LoopKeyframe& k : keyframes) tracks.push_back(&k.u);
  const WindowTracks w = LoopPoints(tracks, outliers, loop, o);
  std::vector<BaCamera> cams = r.cameras;
  for (size_t i = 0; i < cams.size(); ++i) {
    cams[i].rotation_source = cams[i].focal_source = -1;
    // Bearings: a centre enters no residual; held with the first's.
    cams[i].center_source = with_depth || i == 0 ? -1 : 0;
    cams[i].fixed = i < 2;
    cams[i].fixed_focal = true;
  }
  std::vector<BaPoint> points;
  std::vector<BaObservation> all, kept;
  InitWindowPoints(cams, w, tracks, with_depth, 0, &points, &all);
  const double fallback_rho = with_depth ? 0.2 / MedianDepth(keyframes, points) : 0;
  InitWindowPoints(cams, w, tracks, with_depth, fallback_rho, &points, &all);
  BaOptions ba;
  ba.use_depth = with_depth;
  ba.max_iterations = o.ba_iterations;
  ba.num_threads = o.num_threads;
  kept = all;
  BaSummary s = SolveDroppingOutliers(ba, &cams, &points, &kept);
  if (!s.success) return r;
  DropInconsistentTracks(ba, o.track_rms_cut, &cams, &points, all, &kept, &s);
  if (!s.success) return r;
  std::set<int> kept_points;
  for (const BaObservation& ob : kept) kept_points.insert(ob.point);
  r.points = static_cast<int>(points.size());
  r.points_kept = static_cast<int>(kept_points.size());
  r.observations = static_cast<int>(kept.size());
  r.rms_before_px = s.rms_before * kReferenceWidthPx;
  r.rms_after_px = s.rms_after * kReferenceWidthPx;
  for (size_t i = 0; i < cams.size(); ++i) {
    r.cameras[i].world_from_cam = cams[i].world_from_cam;
    if (with_depth) r.cameras[i].center = cams[i].center;
  }
  r.adjusted = true;
  return r;
}

}  // namespace hapcine
