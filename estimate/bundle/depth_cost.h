#pragma once
// Reprojection residuals of the bundle adjustment with analytic Jacobians.
// DepthCostFunction: an anchored inverse-depth point in a camera with free
// rotation, centre and log focal (the bundle
// adjustment's most frequent residual: auto-differentiation of it cost ~7 % of
// `hapcine estimate`'s CPU). Conventions of bundle_adjustment.h:
//   parameters  q (x, y, z, w; unit, EigenQuaternionManifold), c (3),
//               log f (1), X = (d, rho) (unit 4-vector, rho >= 0)
//   point       v = d + rho (anchor - c) in world axes, p = R_wc^T v
//   residual    (f p.xy / p.z - u) * inv_scale
// Evaluate() fails (like the auto-diff version did) for rho < 0 or a point
// not in front of the camera.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

namespace hapcine {

// What the three depth residuals below keep: the observation u, the point's
// anchor and 1 / the residual scale. kBlockSizes: their parameter blocks.
template <int... kBlockSizes>
class AnchoredDepthCost : public ceres::SizedCostFunction<2, kBlockSizes...> {
 public:
  AnchoredDepthCost(const Eigen::Vector2d& u, const Eigen::Vector3d& anchor, double inv_scale)
      : u_(u), anchor_(anchor), inv_scale_(inv_scale) {}

 protected:
  Eigen::Vector2d u_;
  Eigen::Vector3d anchor_;
  double inv_scale_;
};

class DepthCostFunction : public AnchoredDepthCost<4, 3, 1, 4> {
 public:
  using AnchoredDepthCost::AnchoredDepthCost;
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
};

// The same residual with rotation and centre in one block (q x, y, z, w, c;
// ProductManifold of EigenQuaternionManifold and R^3): where a camera owns
// both, one 6-dof block instead of two halves the Schur eliminator's cells.
class PoseDepthCostFunction : public AnchoredDepthCost<7, 1, 4> {
 public:
  using AnchoredDepthCost::AnchoredDepthCost;
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
};

// The same residual with rotation, centre and log focal in one block (q x,
// y, z, w, c, log f; ProductManifold of EigenQuaternionManifold and R^4):
// where a keyframe owns all three (general+zoom segments), one 7-dof block
// instead of a 6-dof and a 1-dof one, again ~4x fewer Schur cells.
class PoseFocalDepthCostFunction : public AnchoredDepthCost<8, 4> {
 public:
  using AnchoredDepthCost::AnchoredDepthCost;
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
};

// Rotation-only window: the bearing d alone (a point at infinity relative to a
// fixed centre). Parameters q (4), log f (1), d (3, SphereManifold<3>).
class BearingCostFunction : public ceres::SizedCostFunction<2, 4, 1, 3> {
 public:
  BearingCostFunction(const Eigen::Vector2d& u, double inv_scale) : u_(u), inv_scale_(inv_scale) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Eigen::Vector2d u_;
  double inv_scale_;
};

}  // namespace hapcine
