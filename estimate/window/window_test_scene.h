#pragma once
// Synthetic windows for the window tests: keyframes that move and turn, one
// focal shared by all, and the points they see (normalised units).

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

#include "core/rotation.h"
#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine::window_test {

constexpr double kPx = 1.0 / 960;  // one pixel at 960 px width, normalised units
constexpr double kFocal = 0.6;     // about 80 degrees of view

struct TestWindow {
  std::vector<BaCamera> cams;
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
  BaOptions ba;
};

// `n` keyframes, each 0.3 ahead and 0.05 right of the one before and
// turned by `turn_deg` about the vertical (OpenCV axes); one focal shared by
// every keyframe, the first pose held.
inline std::vector<BaCamera> MovingCameras(int n, double turn_deg) {
  std::vector<BaCamera> cams(n);
  for (int k = 0; k < n; ++k) {
    cams[k].world_from_cam =
        Eigen::Quaterniond(Eigen::AngleAxisd(k * turn_deg * kPi / 180, Eigen::Vector3d::UnitY()));
    cams[k].log_focal = std::log(kFocal);
    if (k > 0) {
      cams[k].center =
          cams[k - 1].center + cams[k - 1].world_from_cam * Eigen::Vector3d(0.05, 0, 0.3);
      cams[k].focal_source = k - 1;
    }
  }
  cams[0].fixed = true;
  return cams;
}

// Where `cam` sees `X` (normalised image coordinates); none when the point
// is closer than 0.5 ahead or outside the picture.
inline std::optional<Eigen::Vector2d> SeenAt(const BaCamera& cam, const Eigen::Vector3d& X) {
  const Eigen::Vector3d p = cam.world_from_cam.conjugate() * (X - cam.center);
  if (p.z() < 0.5) return std::nullopt;
  const Eigen::Vector2d uv = kFocal * p.head<2>() / p.z();
  if (uv.cwiseAbs().maxCoeff() >= 0.5) return std::nullopt;
  return uv;
}

// An observation built field by field: aggregate braces such as
// `{camera, point, {}}` would give `u` Eigen's default construction (its
// coefficients uninitialised) instead of the member's zero.
inline BaObservation Observation(int camera, int point,
                                 const Eigen::Vector2d& uv = Eigen::Vector2d::Zero()) {
  BaObservation o;
  o.camera = camera;
  o.point = point;
  o.u = uv;
  return o;
}

// Adds `X` with `track`, its observations (their point: the index it gets,
// `w->points.size()`), where it has two or more: a point seen once
// constrains nothing.
inline void AddPoint(const Eigen::Vector3d& X, const std::vector<BaObservation>& track,
                     TestWindow* w) {
  if (track.size() < 2) return;
  w->obs.insert(w->obs.end(), track.begin(), track.end());
  BaPoint pt;
  pt.homogeneous = Eigen::Vector4d(X.x(), X.y(), X.z(), 1).normalized();
  w->points.push_back(pt);
}

// The window's solve options: the focal prior at the truth, the scale held
// by the first step's length.
inline BaOptions WindowOptions(const std::vector<BaCamera>& cams) {
  BaOptions ba;
  ba.focal_prior_log = std::log(kFocal);
  ba.scale_a = 0;
  ba.scale_b = 1;
  ba.scale_distance = (cams[1].center - cams[0].center).norm();
  return ba;
}

}  // namespace hapcine::window_test
