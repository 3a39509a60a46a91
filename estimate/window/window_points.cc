#include "estimate/window/window_points.h"

#include <cmath>
#include <Eigen/Geometry>

#include "estimate/geometry/point_selection.h"

namespace hapcine {

WindowTracks SelectWindowPoints(const std::vector<const KeyframeTracks*>& keyframes,
                                const std::set<long>& outliers, int max_points, int grid_cells) {
  WindowTracks w;
  for (size_t i = 0; i < keyframes.size(); ++i)
    for (const auto& [id, u] : *keyframes[i])
      if (!outliers.count(id)) w.seen[id].push_back(static_cast<int>(i));
  std::vector<TrackCandidate> candidates;
  for (const auto& [id, kfs] : w.seen)
    if (kfs.size() >= 2)
      candidates.push_back({id, static_cast<int>(kfs.size()), keyframes[kfs[kfs.size() / 2]]->at(id)});
  for (long id : SelectWindowTracks(std::move(candidates), max_points, grid_cells))
    w.order.push_back({-static_cast<int>(w.seen[id].size()), id});
  for (size_t k = 0; k < w.order.size(); ++k) w.point_of_track[w.order[k].second] = static_cast<int>(k);
  return w;
}

namespace {

Eigen::Vector3d Ray(const BaCamera& cam, const Eigen::Vector2d& u) {
  const double f = std::exp(cam.log_focal);
  return (cam.world_from_cam * Eigen::Vector3d(u.x() / f, u.y() / f, 1)).normalized();
}

}  // namespace

void InitWindowPoints(const std::vector<BaCamera>& cams, const WindowTracks& tracks,
                      const std::vector<const KeyframeTracks*>& keyframes, bool with_depth,
                      double fallback_rho, std::vector<BaPoint>* points_out, std::vector<BaObservation>* obs_out) {
  std::vector<BaPoint>& points = *points_out;
  std::vector<BaObservation>& obs = *obs_out;
  points.clear();
  obs.clear();
  for (const auto& [neg, id] : tracks.order) {
    const auto& kfs = tracks.seen.at(id);
    const BaCamera& ca = cams[kfs[0]];
    const Eigen::Vector3d ray_a = Ray(ca, keyframes[kfs[0]]->at(id));
    double rho = 0;
    if (with_depth) {
      // Midpoint triangulation with the most distant observing keyframe.
      int best = -1;
      double best_base = 0;
      for (int j : kfs) {
        const double base = (cams[j].center - ca.center).norm();
        if (base > best_base) {
          best_base = base;
          best = j;
        }
      }
      if (best >= 0) {
        const BaCamera& cb = cams[best];
        const Eigen::Vector3d ray_b = Ray(cb, keyframes[best]->at(id));
        const Eigen::Vector3d w = cb.center - ca.center;
        const double bb = ray_a.dot(ray_b), d1 = ray_a.dot(w), d2 = ray_b.dot(w);
        const double den = 1 - bb * bb;
        if (den > 1e-8) {
          const double lambda = (d1 - bb * d2) / den;
          if (lambda > 0 && std::isfinite(lambda)) rho = 1 / lambda;
        }
      }
      if (!(rho > 0)) rho = fallback_rho;
    }
    BaPoint p;
    p.anchor = ca.center;
    p.homogeneous = Eigen::Vector4d(ray_a.x(), ray_a.y(), ray_a.z(), rho).normalized();
    for (int j : kfs) obs.push_back({j, static_cast<int>(points.size()), keyframes[j]->at(id)});
    points.push_back(p);
  }
}

}  // namespace hapcine
