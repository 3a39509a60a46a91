#include "core/rotation.h"

#include <algorithm>
#include <cmath>

namespace hapcine {

Eigen::Quaterniond QuaternionFromPanTiltRoll(const PanTiltRoll& a) {
  const Eigen::Quaterniond q =
      Eigen::AngleAxisd(DegToRad(a.pan_deg), Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(DegToRad(a.tilt_deg), Eigen::Vector3d::UnitX()) *
      Eigen::AngleAxisd(DegToRad(a.roll_deg), Eigen::Vector3d::UnitZ());
  return CanonicalQuaternion(q);
}

PanTiltRoll PanTiltRollFromQuaternion(const Eigen::Quaterniond& q) {
  // R = Ry(p) Rx(t) Rz(r):
  //   R(1,2) = -sin t,  R(0,2) = cos t sin p,  R(2,2) = cos t cos p,
  //   R(1,0) = cos t sin r,  R(1,1) = cos t cos r.
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  PanTiltRoll out;
  const double sin_tilt = std::clamp(-R(1, 2), -1.0, 1.0);
  out.tilt_deg = RadToDeg(std::asin(sin_tilt));
  if (std::abs(sin_tilt) < 1.0 - 1e-12) {
    out.pan_deg = RadToDeg(std::atan2(R(0, 2), R(2, 2)));
    out.roll_deg = RadToDeg(std::atan2(R(1, 0), R(1, 1)));
  } else {
    // Gimbal lock: only pan - roll (or pan + roll) is defined.
    out.pan_deg = RadToDeg(std::atan2(-R(2, 0), R(0, 0)));
    out.roll_deg = 0;
  }
  return out;
}

Eigen::Quaterniond CanonicalQuaternion(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond n = q.normalized();
  if (n.w() < 0) n.coeffs() = -n.coeffs();
  return n;
}

double AngleBetweenDeg(const Eigen::Quaterniond& a,
                       const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = a.normalized().conjugate() * b.normalized();
  // atan2 form stays accurate for tiny angles, unlike acos(w).
  const double s = d.vec().norm();
  return RadToDeg(2.0 * std::atan2(s, std::abs(d.w())));
}

double OpticalAxisAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Vector3d za = a * Eigen::Vector3d::UnitZ(), zb = b * Eigen::Vector3d::UnitZ();
  return RadToDeg(std::acos(std::clamp(za.dot(zb), -1.0, 1.0)));
}

double FovDegFromFocalPx(double focal_px, double width_px) {
  return RadToDeg(2.0 * std::atan(width_px / (2.0 * focal_px)));
}

double FocalPxFromFovDeg(double fov_deg, double width_px) {
  return width_px / (2.0 * std::tan(DegToRad(fov_deg) / 2.0));
}

}  // namespace hapcine
