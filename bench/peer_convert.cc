#include "bench/peer_convert.h"

#include <cmath>

#include "core/rotation.h"

namespace hapcine::bench {

Eigen::Quaterniond RelativeRotationGl(const Eigen::Matrix3d& world_from_first_cv,
                                      const Eigen::Matrix3d& world_from_i_cv) {
  // first_from_i: camera i's axes seen from the first camera (the new world).
  const Eigen::Matrix3d first_from_i = world_from_first_cv.transpose() * world_from_i_cv;
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();
  Eigen::Quaterniond q(flip * first_from_i * flip);
  return CanonicalQuaternion(q.normalized());
}

SimilarityCamera CameraFromSimilarity(const Eigen::Matrix3d& frame0_to_i, double width,
                                      double height, double focal0_px) {
  const Eigen::Matrix2d lin = frame0_to_i.topLeftCorner<2, 2>();
  const Eigen::Vector2d centre(0.5 * width, 0.5 * height);
  // Where the centre of frame 0 lands, relative to the centre of frame i.
  const Eigen::Vector2d t = lin * centre + frame0_to_i.topRightCorner<2, 1>() - centre;
  SimilarityCamera cam;
  const double scale = std::hypot(lin(0, 0), lin(1, 0));
  cam.focal_px = focal0_px * scale;
  cam.roll_deg = RadToDeg(std::atan2(lin(1, 0), lin(0, 0)));
  cam.pan_deg = RadToDeg(std::atan(t.x() / cam.focal_px));
  cam.tilt_deg = RadToDeg(std::atan(t.y() / cam.focal_px));
  return cam;
}

CameraFrame InterpolateFrames(const CameraFrame& a, const CameraFrame& b, double u) {
  CameraFrame f = a;
  f.world_from_cam = a.world_from_cam.slerp(u, b.world_from_cam).normalized();
  f.center = (1 - u) * a.center + u * b.center;
  const double fa = a.focal_px.value_or(0), fb = b.focal_px.value_or(0);
  if (fa > 0 && fb > 0) f.focal_px = std::exp((1 - u) * std::log(fa) + u * std::log(fb));
  // Field of view from the interpolated focal keeps the two consistent.
  if (f.focal_px && a.fov_deg > 0) {
    const double width = 2 * fa * std::tan(DegToRad(a.fov_deg) / 2);
    f.fov_deg = FovDegFromFocalPx(*f.focal_px, width);
  } else {
    f.fov_deg = (1 - u) * a.fov_deg + u * b.fov_deg;
  }
  f.time_s = (1 - u) * a.time_s + u * b.time_s;
  return f;
}

}  // namespace hapcine::bench
