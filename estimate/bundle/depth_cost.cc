#include "estimate/bundle/depth_cost.h"

#include <Eigen/Dense>
#include <cmath>

namespace hapcine {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

using RowMatrix24 = Eigen::Matrix<double, 2, 4, Eigen::RowMajor>;

// Residual (f p.xy / p.z - u) * inv_scale of the world-axes vector v seen by
// the camera rotation q (x, y, z, w); false when v is not in front of it.
// With `dr_dq` (may be null) and `dr_dv`: the Jacobians in q's four stored
// coordinates and in v. d r / d log f is the projection itself times inv_scale.
bool ProjectResidual(const double* q, double f, const Eigen::Vector3d& v, const Eigen::Vector2d& u,
                     double inv_scale, double* r, RowMatrix24* dr_dq, Eigen::Matrix<double, 2, 3>* dr_dv) {
  // p = conj(q) * v as Eigen evaluates it for a (unit) quaternion: with
  // a = -(x, y, z), p = v + 2 w (a x v) + 2 a x (a x v). The Jacobians are of
  // this expression (what auto-diff gave).
  const Eigen::Vector3d a(-q[0], -q[1], -q[2]);
  const double w = q[3];
  const Eigen::Vector3d axv = a.cross(v);
  const Eigen::Vector3d p = v + 2 * w * axv + 2 * a.cross(axv);
  if (!(p.z() > 1e-9 * std::sqrt(p.squaredNorm() + 1e-300))) return false;
  const double iz = 1 / p.z();
  r[0] = (f * p.x() * iz - u.x()) * inv_scale;
  r[1] = (f * p.y() * iz - u.y()) * inv_scale;
  if (dr_dv == nullptr) return true;
  Eigen::Matrix<double, 2, 3> dr_dp;
  dr_dp << 1, 0, -p.x() * iz, 0, 1, -p.y() * iz;
  dr_dp *= f * iz * inv_scale;
  // d p / d v = I + 2 w [a]x + 2 [a]x^2 (= R_wc^T for a unit quaternion).
  const Eigen::Matrix3d sa = Skew(a);
  *dr_dv = dr_dp * (Eigen::Matrix3d::Identity() + 2 * w * sa + 2 * sa * sa);
  if (dr_dq != nullptr) {
    // d p / d a = -2 w [v]x + 2 ((a.v) I + a v^T - 2 v a^T); d a / d (x, y, z) = -I.
    const Eigen::Matrix3d dp_da =
        -2 * w * Skew(v) +
        2 * (a.dot(v) * Eigen::Matrix3d::Identity() + a * v.transpose() - 2 * v * a.transpose());
    Eigen::Matrix<double, 3, 4> dp_dq;
    dp_dq.leftCols<3>() = -dp_da;
    dp_dq.col(3) = 2 * axv;
    *dr_dq = dr_dp * dp_dq;
  }
  return true;
}

// d r / d log f = f p.xy / p.z * inv_scale = r + u * inv_scale.
void FocalJacobian(const double* r, const Eigen::Vector2d& u, double inv_scale, double* j) {
  j[0] = r[0] + u.x() * inv_scale;
  j[1] = r[1] + u.y() * inv_scale;
}

// The depth residual with q, c, log f, X given separately; Jacobian outputs
// (row-major 2x4, 2x3, 2x1, 2x4) may be null.
bool DepthResidual(const double* q, const double* c_in, double log_f, const double* X,
                   const Eigen::Vector3d& anchor, const Eigen::Vector2d& u, double inv_scale,
                   double* residuals, double* j_q, double* j_c, double* j_f, double* j_x) {
  const Eigen::Vector3d c(c_in[0], c_in[1], c_in[2]);
  const double f = std::exp(log_f);
  const double rho = X[3];
  if (rho < 0) return false;  // beyond infinity: behind every camera
  const Eigen::Vector3d v = Eigen::Vector3d(X[0], X[1], X[2]) + rho * (anchor - c);
  RowMatrix24 dr_dq;
  Eigen::Matrix<double, 2, 3> dr_dv;
  const bool jac = j_q || j_c || j_f || j_x;
  if (!ProjectResidual(q, f, v, u, inv_scale, residuals, j_q ? &dr_dq : nullptr, jac ? &dr_dv : nullptr))
    return false;
  if (j_q != nullptr) Eigen::Map<RowMatrix24>(j_q, 2, 4) = dr_dq;
  if (j_c != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> j(j_c);
    j = -rho * dr_dv;
  }
  if (j_f != nullptr) FocalJacobian(residuals, u, inv_scale, j_f);
  if (j_x != nullptr) {
    Eigen::Map<RowMatrix24> j(j_x);
    j.leftCols<3>() = dr_dv;
    j.col(3) = dr_dv * (anchor - c);
  }
  return true;
}

}  // namespace

bool DepthCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  auto jac = [&](int k) { return jacobians != nullptr ? jacobians[k] : nullptr; };
  return DepthResidual(parameters[0], parameters[1], parameters[2][0], parameters[3], anchor_, u_,
                       inv_scale_, residuals, jac(0), jac(1), jac(2), jac(3));
}

bool PoseDepthCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const double* pose = parameters[0];
  double j_q[8], j_c[6];
  double* j_pose = jacobians != nullptr ? jacobians[0] : nullptr;
  if (!DepthResidual(pose, pose + 4, parameters[1][0], parameters[2], anchor_, u_, inv_scale_, residuals,
                     j_pose ? j_q : nullptr, j_pose ? j_c : nullptr,
                     jacobians != nullptr ? jacobians[1] : nullptr,
                     jacobians != nullptr ? jacobians[2] : nullptr))
    return false;
  if (j_pose != nullptr) {
    for (int r = 0; r < 2; ++r) {  // row-major 2x7: the 2x4 then the 2x3
      for (int k = 0; k < 4; ++k) j_pose[7 * r + k] = j_q[4 * r + k];
      for (int k = 0; k < 3; ++k) j_pose[7 * r + 4 + k] = j_c[3 * r + k];
    }
  }
  return true;
}

bool PoseFocalDepthCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                          double** jacobians) const {
  const double* pose = parameters[0];
  double j_q[8], j_c[6], j_f[2];
  double* j_pose = jacobians != nullptr ? jacobians[0] : nullptr;
  if (!DepthResidual(pose, pose + 4, pose[7], parameters[1], anchor_, u_, inv_scale_, residuals,
                     j_pose ? j_q : nullptr, j_pose ? j_c : nullptr, j_pose ? j_f : nullptr,
                     jacobians != nullptr ? jacobians[1] : nullptr))
    return false;
  if (j_pose != nullptr) {
    for (int r = 0; r < 2; ++r) {  // row-major 2x8: the 2x4, the 2x3, the 2x1
      for (int k = 0; k < 4; ++k) j_pose[8 * r + k] = j_q[4 * r + k];
      for (int k = 0; k < 3; ++k) j_pose[8 * r + 4 + k] = j_c[3 * r + k];
      j_pose[8 * r + 7] = j_f[r];
    }
  }
  return true;
}

bool BearingCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const double f = std::exp(parameters[1][0]);
  const Eigen::Vector3d d(parameters[2][0], parameters[2][1], parameters[2][2]);
  RowMatrix24 dr_dq;
  Eigen::Matrix<double, 2, 3> dr_dd;
  const bool jac = jacobians != nullptr;
  if (!ProjectResidual(parameters[0], f, d, u_, inv_scale_, residuals,
                       jac && jacobians[0] ? &dr_dq : nullptr, jac ? &dr_dd : nullptr))
    return false;
  if (!jac) return true;
  if (jacobians[0] != nullptr) Eigen::Map<RowMatrix24>(jacobians[0], 2, 4) = dr_dq;
  if (jacobians[1] != nullptr) FocalJacobian(residuals, u_, inv_scale_, jacobians[1]);
  if (jacobians[2] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> j(jacobians[2]);
    j = dr_dd;
  }
  return true;
}

}  // namespace hapcine
