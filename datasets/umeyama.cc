#include "datasets/umeyama.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace hapcine {

Sim3 AlignUmeyama(const std::vector<Eigen::Vector3d>& src,
                  const std::vector<Eigen::Vector3d>& dst, bool with_scale) {
  Sim3 out;
  const size_t n = std::min(src.size(), dst.size());
  if (n == 0) return out;

  Eigen::Vector3d mean_src = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_dst = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_src += src[i];
    mean_dst += dst[i];
  }
  mean_src /= static_cast<double>(n);
  mean_dst /= static_cast<double>(n);

  // Covariance dst x src and the variance of src (Umeyama eqs. 38-42).
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double var_src = 0;
  double var_dst = 0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = src[i] - mean_src;
    const Eigen::Vector3d b = dst[i] - mean_dst;
    cov += b * a.transpose();
    var_src += a.squaredNorm();
    var_dst += b.squaredNorm();
  }
  cov /= static_cast<double>(n);
  var_src /= static_cast<double>(n);
  var_dst /= static_cast<double>(n);

  // Relative threshold: "all points equal" must hold for coordinates of any
  // magnitude (1e6 offsets in world units are not rare in mocap data).
  const double magnitude = std::max({1.0, mean_src.squaredNorm(), mean_dst.squaredNorm()});
  const double kTiny = 1e-24 * magnitude;
  if (var_src <= kTiny) {
    // Source is a single point: rotation and scale are unobservable.
    out.translation = mean_dst - mean_src;
    return out;
  }
  if (with_scale && var_dst <= kTiny) {
    // Target is a single point: the best similarity shrinks src to it.
    out.scale = 0.0;
    out.translation = mean_dst;
    return out;
  }

  Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  Eigen::Vector3d s_diag = Eigen::Vector3d::Ones();
  if (U.determinant() * V.determinant() < 0) s_diag(2) = -1;  // no reflections
  out.rotation = U * s_diag.asDiagonal() * V.transpose();
  if (with_scale) {
    const double s = svd.singularValues().dot(s_diag) / var_src;
    out.scale = std::isfinite(s) ? std::max(0.0, s) : 1.0;
  }
  out.translation = mean_dst - out.scale * (out.rotation * mean_src);
  if (!out.rotation.allFinite() || !out.translation.allFinite()) {
    out = Sim3();
    out.translation = mean_dst - mean_src;
  }
  return out;
}

}  // namespace hapcine
