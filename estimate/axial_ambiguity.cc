#include "estimate/axial_ambiguity.h"

#include <algorithm>
#include <cmath>

namespace hapcine {
namespace {

constexpr double kFarPercentile = 0.1;

}  // namespace

bool IsAxialMotion(const std::vector<BaCamera>& cams, int pivot, double min_axial_share) {
  if (pivot < 0 || pivot + 1 >= static_cast<int>(cams.size())) return false;
  const BaCamera& p = cams[pivot];
  Eigen::Vector3d far = Eigen::Vector3d::Zero();
  for (size_t k = pivot + 1; k < cams.size(); ++k)
    if ((cams[k].center - p.center).norm() > far.norm()) far = cams[k].center - p.center;
  const double len = far.norm();
  if (!(len > 1e-12)) return false;
  const Eigen::Vector3d in_cam = p.world_from_cam.conjugate() * far;
  return std::abs(in_cam.z()) >= min_axial_share * len;
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
  const size_t k = std::min(s.size() - 1, static_cast<size_t>(std::clamp(percentile, 0.0, 1.0) * s.size()));
  std::nth_element(s.begin(), s.begin() + k, s.end());
  return s[k];
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

}  // namespace hapcine
