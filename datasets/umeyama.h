#pragma once
// Least-squares similarity alignment of two point sets (Umeyama 1991,
// "Least-squares estimation of transformation parameters between two point
// patterns"): find s, R, t minimising sum_i |dst_i - (s R src_i + t)|^2.
//
// This is the alignment evo uses for `evo_ape -as` (Sim(3)) and `-a` (SE(3)).
// Unlike Eigen::umeyama it never returns NaN: degenerate inputs (no points,
// one point, all points equal) fall back to a pure translation between the
// centroids with R = I and s = 1; collinear inputs keep the rotation that the
// SVD picks (any rotation about the line fits equally well).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace hapcine {

// dst = scale * rotation * src + translation.
struct Sim3 {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const {
    return scale * (rotation * p) + translation;
  }
};

// `with_scale` false gives the rigid (SE(3)) fit with scale fixed to 1.
// Points beyond min(src.size(), dst.size()) are ignored.
Sim3 AlignUmeyama(const std::vector<Eigen::Vector3d>& src,
                  const std::vector<Eigen::Vector3d>& dst, bool with_scale);

}  // namespace hapcine
