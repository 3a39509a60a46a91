#include "estimate/depth_cost.h"

#include <Eigen/Dense>
#include <cmath>

namespace hapcine {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

}  // namespace

bool DepthCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  const double* q = parameters[0];
  const Eigen::Vector3d c(parameters[1][0], parameters[1][1], parameters[1][2]);
  const double f = std::exp(parameters[2][0]);
  const double* X = parameters[3];
  const double rho = X[3];
  if (rho < 0) return false;  // beyond infinity: behind every camera
  const Eigen::Vector3d v = Eigen::Vector3d(X[0], X[1], X[2]) + rho * (anchor_ - c);
  // p = conj(q) * v as Eigen evaluates it for a (unit) quaternion: with
  // a = -(x, y, z), p = v + 2 w (a x v) + 2 a x (a x v). The Jacobians are of
  // this expression in the four stored coordinates (what auto-diff gave).
  const Eigen::Vector3d a(-q[0], -q[1], -q[2]);
  const double w = q[3];
  const Eigen::Vector3d axv = a.cross(v);
  const Eigen::Vector3d p = v + 2 * w * axv + 2 * a.cross(axv);
  if (!(p.z() > 1e-9 * std::sqrt(p.squaredNorm() + 1e-300))) return false;
  const double iz = 1 / p.z();
  const double u0 = f * p.x() * iz, u1 = f * p.y() * iz;
  residuals[0] = (u0 - u_.x()) * inv_scale_;
  residuals[1] = (u1 - u_.y()) * inv_scale_;
  if (jacobians == nullptr) return true;

  // d residual / d p (2x3).
  Eigen::Matrix<double, 2, 3> dr_dp;
  dr_dp << 1, 0, -p.x() * iz, 0, 1, -p.y() * iz;
  dr_dp *= f * iz * inv_scale_;
  // d p / d v = I + 2 w [a]x + 2 [a]x^2 (= R_wc^T for a unit quaternion).
  const Eigen::Matrix3d sa = Skew(a);
  const Eigen::Matrix3d dp_dv = Eigen::Matrix3d::Identity() + 2 * w * sa + 2 * sa * sa;
  const Eigen::Matrix<double, 2, 3> dr_dv = dr_dp * dp_dv;
  if (jacobians[0] != nullptr) {
    // d p / d a = -2 w [v]x + 2 ((a.v) I + a v^T - 2 v a^T); d a / d (x, y, z) = -I.
    const Eigen::Matrix3d dp_da =
        -2 * w * Skew(v) +
        2 * (a.dot(v) * Eigen::Matrix3d::Identity() + a * v.transpose() - 2 * v * a.transpose());
    Eigen::Matrix<double, 3, 4> dp_dq;
    dp_dq.leftCols<3>() = -dp_da;
    dp_dq.col(3) = 2 * axv;
    Eigen::Map<Eigen::Matrix<double, 2, 4, Eigen::RowMajor>> j(jacobians[0]);
    j = dr_dp * dp_dq;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> j(jacobians[1]);
    j = -rho * dr_dv;
  }
  if (jacobians[2] != nullptr) {
    jacobians[2][0] = u0 * inv_scale_;
    jacobians[2][1] = u1 * inv_scale_;
  }
  if (jacobians[3] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 4, Eigen::RowMajor>> j(jacobians[3]);
    j.leftCols<3>() = dr_dv;
    j.col(3) = dr_dv * (anchor_ - c);
  }
  return true;
}

}  // namespace hapcine
