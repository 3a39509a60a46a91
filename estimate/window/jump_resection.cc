#include "estimate/window/jump_resection.h"

#include <cmath>
#include <opencv2/calib3d.hpp>

#include "estimate/geometry/reference_width.h"

namespace hapcine {
namespace {

Eigen::Vector3d Ray(const BaCamera& cam, const Eigen::Vector2d& u) {
  const double f = std::exp(cam.log_focal);
  return (cam.world_from_cam * Eigen::Vector3d(u.x() / f, u.y() / f, 1)).normalized();
}

// Midpoint of the two rays' closest approach, when they meet in front of
// both cameras at a parallax of at least 1 degree.
std::optional<Eigen::Vector3d> Triangulate(const BaCamera& a, const Eigen::Vector2d& ua, const BaCamera& b,
                                           const Eigen::Vector2d& ub) {
  const Eigen::Vector3d ra = Ray(a, ua), rb = Ray(b, ub), w = b.center - a.center;
  const double c = ra.dot(rb), den = 1 - c * c;
  if (c > std::cos(M_PI / 180)) return std::nullopt;
  const double la = (ra.dot(w) - c * rb.dot(w)) / den, lb = (c * ra.dot(w) - rb.dot(w)) / den;
  if (!(la > 0 && lb > 0)) return std::nullopt;
  return 0.5 * (a.center + la * ra + b.center + lb * rb);
}

}  // namespace

std::optional<BaCamera> ResectKeyframe(const std::vector<BaCamera>& cams,
                                       const std::vector<const KeyframeTracks*>& tracks, int i, int min_inliers) {
  std::vector<cv::Point3d> world;
  std::vector<cv::Point2d> image;
  for (const auto& [id, u] : *tracks[i]) {
    // The earlier keyframes that see it: the first and the one farthest from it.
    int first = -1, far = -1;
    double base = 0;
    for (int j = 0; j < i; ++j) {
      if (!tracks[j]->count(id)) continue;
      if (first < 0) {
        first = j;
        continue;
      }
      const double d = (cams[j].center - cams[first].center).norm();
      if (d > base) base = d, far = j;
    }
    if (far < 0) continue;
    const auto x = Triangulate(cams[first], tracks[first]->at(id), cams[far], tracks[far]->at(id));
    if (!x) continue;
    world.emplace_back(x->x(), x->y(), x->z());
    image.emplace_back(u.x(), u.y());
  }
  if (static_cast<int>(world.size()) < min_inliers) return std::nullopt;
  const double f = std::exp(cams[i].log_focal);
  const cv::Matx33d k(f, 0, 0, 0, f, 0, 0, 0, 1);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(world, image, k, cv::noArray(), rvec, tvec, false, 200, 2.0 / kReferenceWidthPx, 0.999,
                          inliers, cv::SOLVEPNP_EPNP) ||
      static_cast<int>(inliers.size()) < min_inliers)
    return std::nullopt;
  cv::Mat r;
  cv::Rodrigues(rvec, r);
  Eigen::Matrix3d cam_from_world;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) cam_from_world(a, b) = r.at<double>(a, b);
  const Eigen::Vector3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  BaCamera out = cams[i];
  out.world_from_cam = Eigen::Quaterniond(cam_from_world.transpose()).normalized();
  out.center = -cam_from_world.transpose() * t;
  if (!out.world_from_cam.coeffs().allFinite() || !out.center.allFinite()) return std::nullopt;
  return out;
}

void MoveChainFrom(int i, const BaCamera& placed, std::vector<BaCamera>* cams) {
  const BaCamera old = (*cams)[i];
  const Eigen::Quaterniond turn = placed.world_from_cam * old.world_from_cam.inverse();
  for (size_t j = i; j < cams->size(); ++j) {
    BaCamera& c = (*cams)[j];
    c.center = placed.center + turn * (c.center - old.center);
    c.world_from_cam = (turn * c.world_from_cam).normalized();
  }
}

}  // namespace hapcine
