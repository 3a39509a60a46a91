#include "estimate/window/axial_ambiguity.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"
#include "estimate/geometry/motion_plane.h"

namespace hapcine {
namespace {

constexpr double kFarPercentile = 0.1;

// The move from the pivot's centre to the centre farthest from it among the
// cameras after it, in the pivot camera's frame (zero when none moves).
Eigen::Vector3d FarthestMoveInPivot(const std::vector<BaCamera>& cams, int pivot) {
  const BaCamera& p = cams[pivot];
  Eigen::Vector3d far = Eigen::Vector3d::Zero();
  for (size_t k = pivot + 1; k < cams.size(); ++k)
    if ((cams[k].center - p.center).norm() > far.norm()) far = cams[k].center - p.center;
  return p.world_from_cam.conjugate() * far;
}

}  // namespace

bool IsAxialMotion(const std::vector<BaCamera>& cams, int pivot, double min_axial_share) {
  if (pivot < 0 || pivot + 1 >= static_cast<int>(cams.size())) return false;
  const Eigen::Vector3d in_cam = FarthestMoveInPivot(cams, pivot);
  const double len = in_cam.norm();
  if (!(len > 1e-12)) return false;
  return std::abs(in_cam.z()) >= min_axial_share * len;
}

int AxialDirection(const std::vector<BaCamera>& cams, int pivot) {
  if (pivot < 0 || pivot + 1 >= static_cast<int>(cams.size())) return 0;
  const double z = FarthestMoveInPivot(cams, pivot).z();
  return z > 0 ? 1 : z < 0 ? -1 : 0;
}

std::vector<char> RuledOutOtherBranch(const std::vector<char>& ruled_out, const std::vector<int>& direction,
                                      const std::vector<double>& score) {
  const size_t n = std::min({ruled_out.size(), direction.size(), score.size()});
  int best = -1;
  for (size_t c = 0; c < n; ++c)
    if (!ruled_out[c] && (best < 0 || score[c] > score[best])) best = static_cast<int>(c);
  if (best < 0 || direction[best] == 0) return ruled_out;
  std::vector<char> out = ruled_out;
  for (size_t c = 0; c < n; ++c) out[c] = ruled_out[c] && direction[c] != direction[best];
  return out;
}

double RadialScalePercentile(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& matches,
                             double percentile, double min_radius) {
  std::vector<double> s;
  for (const auto& [u1, u2] : matches) {
    const double r2 = u1.squaredNorm();
    if (r2 < min_radius * min_radius) continue;
    const double v = u2.dot(u1) / r2;
    if (std::isfinite(v) && v > 0) s.push_back(v);
  }
  if (s.empty()) return 1;
  return Quantile(std::move(s), percentile);
}

std::vector<BaCamera> MirroredAxialBranch(
    const std::vector<BaCamera>& cams, int pivot,
    const std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>>& matches) {
  std::vector<BaCamera> out = cams;
  if (pivot < 0) return out;
  const Eigen::Vector3d c0 = cams[pivot].center;
  for (size_t k = pivot + 1; k < out.size(); ++k) {
    out[k].center = c0 - (cams[k].center - c0);
    // Direction of this step along the previous camera's optical axis.
    const Eigen::Vector3d step = out[k].world_from_cam.conjugate() * (out[k].center - out[k - 1].center);
    const bool forward = step.z() > 0;  // OpenCV axes: +z looks forward
    const double s = k < matches.size()
                         ? RadialScalePercentile(matches[k], forward ? kFarPercentile : 1 - kFarPercentile)
                         : 1;
    // x2 = (f2 / f1) * (depth ratio) * x1; the far points' depth ratio is 1.
    out[k].log_focal = out[k - 1].log_focal + std::log(s);
  }
  return out;
}

std::vector<Eigen::Vector3d> InverseDepthsIn(const BaCamera& cam, const std::vector<BaPoint>& points,
                                             const std::vector<char>& used) {
  std::vector<Eigen::Vector3d> xyw;
  for (size_t i = 0; i < points.size(); ++i) {
    if (i < used.size() && !used[i]) continue;
    // Homogeneous world point (anchor rho + d, rho), into the camera.
    const double rho = std::max(0.0, points[i].homogeneous(3));
    const Eigen::Vector3d x =
        cam.world_from_cam.conjugate() * (points[i].Direction() + rho * (points[i].anchor - cam.center));
    if (!(x.z() > 1e-12)) continue;
    xyw.emplace_back(x.x() / x.z(), x.y() / x.z(), rho / x.z());
  }
  return xyw;
}

std::optional<std::vector<BaCamera>> ShiftedAxialSolution(const std::vector<BaCamera>& cams, int pivot,
                                                          double delta) {
  if (pivot < 0 || pivot >= static_cast<int>(cams.size()) || !std::isfinite(delta)) return std::nullopt;
  const BaCamera& p = cams[pivot];
  std::vector<BaCamera> out = cams;
  for (BaCamera& c : out) {
    const Eigen::Vector3d in_pivot = p.world_from_cam.conjugate() * (c.center - p.center);
    if (c.fixed) {
      if (in_pivot.norm() > 1e-9) return std::nullopt;
      continue;
    }
    const double scale = 1 + delta * in_pivot.z();
    if (!(scale > 1e-3)) return std::nullopt;
    c.center = p.center + p.world_from_cam * (in_pivot / scale);
    c.log_focal -= std::log(scale);
  }
  return out;
}

std::vector<BaPoint> ShiftedAxialPoints(const BaCamera& pivot, double delta, const std::vector<BaPoint>& points) {
  const Eigen::Quaterniond cam_from_world = pivot.world_from_cam.conjugate();
  // Homogeneous point (x, w) in the pivot's frame -> (x, w + delta x_z), back to the world.
  auto map = [&](const Eigen::Vector3d& x_world, double w) {
    const Eigen::Vector3d x = cam_from_world * (x_world - w * pivot.center);
    const double w2 = w + delta * x.z();
    return std::make_pair(Eigen::Vector3d(pivot.world_from_cam * x + w2 * pivot.center), w2);
  };
  std::vector<BaPoint> out = points;
  for (BaPoint& p : out) {
    const double rho = p.homogeneous(3);
    const auto [x, w] = map(p.Direction() + rho * p.anchor, rho);
    const auto [a, aw] = map(p.anchor, 1.0);
    p.anchor = a / aw;
    Eigen::Vector4d h;
    h << x - w * p.anchor, w;
    if (h.norm() > 0) p.homogeneous = h.normalized();
  }
  return out;
}

std::optional<PlaneShift> ShiftForMotionPlane(const std::vector<BaCamera>& cams, int pivot,
                                              const std::vector<Eigen::Vector3d>& xyw) {
  if (!IsAxialMotion(cams, pivot)) return std::nullopt;
  const Eigen::Vector3d m = FarthestMoveInPivot(cams, pivot).normalized();
  if (xyw.empty()) return std::nullopt;
  PlaneShift s;
  s.points = static_cast<int>(xyw.size());
  s.min_w = s.max_w = xyw.front().z();
  for (const auto& v : xyw) {
    s.min_w = std::min(s.min_w, v.z());
    s.max_w = std::max(s.max_w, v.z());
  }
  // (n + delta e_z) . m = 0: the shifted plane contains the direction of motion.
  auto delta_of = [&](const Eigen::Vector3d& n) { return -n.dot(m) / m.z(); };
  // Only planes that can be parallel to the move: shifted so, no point may
  // pass beyond infinity.
  auto parallel_possible = [&](const Eigen::Vector3d& n) {
    const double d = delta_of(n);
    return std::isfinite(d) && d >= -s.min_w;
  };
  const std::optional<InverseDepthPlane> plane = FindSlopedPlane(xyw, {}, parallel_possible);
  if (!plane) return std::nullopt;
  s.plane = plane->n;
  s.inliers = plane->inliers;
  s.delta = delta_of(plane->n);
  return s;
}

}  // namespace hapcine
