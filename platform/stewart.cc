#include "platform/stewart.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>

namespace hapcine {

Eigen::Matrix3d PoseRotation(const PlatformPose& pose) {
  return (Eigen::AngleAxisd(pose[3], Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(pose[4], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pose[5], Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

LegLengths StewartLegLengths(const StewartGeometry& g, const PlatformPose& pose) {
  const Eigen::Matrix3d r = PoseRotation(pose);
  const Eigen::Vector3d p = pose.head<3>();
  LegLengths legs;
  for (int i = 0; i < 6; ++i) legs[i] = (p + r * g.top_m[i] - g.base_m[i]).norm();
  return legs;
}

bool LegsWithinStroke(const StewartGeometry& g, const LegLengths& legs, double margin_m) {
  for (double l : legs) {
    if (!(l >= g.min_leg_m + margin_m && l <= g.max_leg_m - margin_m)) return false;
  }
  return true;
}

std::optional<PlatformPose> StewartForwardKinematics(const StewartGeometry& g,
                                                     const LegLengths& legs,
                                                     const PlatformPose& guess) {
  PlatformPose x = guess;
  constexpr double kStep = 1e-7;  // central differences for the Jacobian
  for (int it = 0; it < 50; ++it) {
    const LegLengths now = StewartLegLengths(g, x);
    Eigen::Matrix<double, 6, 1> residual;
    for (int i = 0; i < 6; ++i) residual[i] = now[i] - legs[i];
    if (residual.cwiseAbs().maxCoeff() < 1e-12) return x;
    Eigen::Matrix<double, 6, 6> jac;
    for (int k = 0; k < 6; ++k) {
      PlatformPose hi = x, lo = x;
      hi[k] += kStep;
      lo[k] -= kStep;
      const LegLengths lh = StewartLegLengths(g, hi), ll = StewartLegLengths(g, lo);
      for (int i = 0; i < 6; ++i) jac(i, k) = (lh[i] - ll[i]) / (2 * kStep);
    }
    x -= jac.fullPivLu().solve(residual);
    if (!x.allFinite()) return std::nullopt;
  }
  return std::nullopt;
}

double StrokeScale(const StewartGeometry& g, const PlatformPose& pose, double margin_m) {
  if (LegsWithinStroke(g, StewartLegLengths(g, pose), margin_m)) return 1.0;
  double lo = 0, hi = 1;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (LegsWithinStroke(g, StewartLegLengths(g, mid * pose), margin_m) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace hapcine
