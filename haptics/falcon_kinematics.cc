#include "haptics/falcon_kinematics.h"

#include <Eigen/LU>
#include <cmath>

namespace hapcine {

double EncoderToAngleRad(int16_t counts) {
  return (counts * kFalconDegPerCount + kFalconAngleOffsetDeg) * M_PI / 180.0;
}

double AngleRadToEncoder(double theta1_rad) {
  return (theta1_rad * 180.0 / M_PI - kFalconAngleOffsetDeg) / kFalconDegPerCount;
}

FalconKinematics::FalconKinematics(const FalconGeometry& g) : g_(g) {
  for (int i = 0; i < 3; ++i) {
    cos_phi_[i] = std::cos(g_.phi_deg[i] * M_PI / 180.0);
    sin_phi_[i] = std::sin(g_.phi_deg[i] * M_PI / 180.0);
  }
}

Eigen::Vector3d FalconKinematics::ToLeg(int i, const Eigen::Vector3d& p) const {
  // Rz(-phi) p + (-r, -s, 0).
  return Eigen::Vector3d(cos_phi_[i] * p.x() + sin_phi_[i] * p.y() - g_.r,
                         -sin_phi_[i] * p.x() + cos_phi_[i] * p.y() - g_.s, p.z());
}

bool FalconKinematics::Inverse(const Eigen::Vector3d& p_m, Eigen::Vector3d* theta_rad) const {
  if (!p_m.allFinite()) return false;
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d q = ToLeg(i, p_m);
    const double cy = (q.y() + g_.f) / g_.b;  // cos theta3
    if (!(std::abs(cy) <= 1.0)) return false;
    const double k = g_.d + g_.e + g_.b * std::sqrt(1.0 - cy * cy);
    // h = (x + c - a cos t)^2 + (z - a sin t)^2 - k^2 = 0 with T = tan(t/2):
    // (A + 2a(x+c)) T^2 - 4 a z T + (A - 2a(x+c)) = 0,
    // A = (x+c)^2 + z^2 + a^2 - k^2.
    const double xc = q.x() + g_.c;
    const double big_a = xc * xc + q.z() * q.z() + g_.a * g_.a - k * k;
    const double l2 = big_a + 2 * g_.a * xc;
    const double l1 = -4 * g_.a * q.z();
    const double l0 = big_a - 2 * g_.a * xc;
    const double disc = l1 * l1 - 4 * l2 * l0;
    if (!(disc >= 0) || std::abs(l2) < 1e-15) return false;
    // The "-" root is the elbow-out configuration of the real device.
    const double t = (-l1 - std::sqrt(disc)) / (2 * l2);
    out[i] = 2 * std::atan(t);
  }
  *theta_rad = out;
  return true;
}

bool FalconKinematics::AngleJacobian(const Eigen::Vector3d& p_m, Eigen::Matrix3d* dtheta_dp) const {
  Eigen::Vector3d theta;
  if (!Inverse(p_m, &theta)) return false;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d q = ToLeg(i, p_m);
    const double st = std::sin(theta[i]), ct = std::cos(theta[i]);
    const double yf = q.y() + g_.f;
    const double root = std::sqrt(g_.b * g_.b - yf * yf);  // b sin theta3
    if (root < 1e-9) return false;
    const double k = g_.d + g_.e + root;
    const double u = q.x() + g_.c - g_.a * ct;
    const double w = q.z() - g_.a * st;
    // Implicit differentiation of h(q, t) = u^2 + w^2 - k^2 = 0:
    // dh/dq = (2u, 2k (y+f)/root, 2w), dh/dt = 2a (u sin t - w cos t),
    // dt/dq = -(dh/dq) / (dh/dt).
    const double dh_dt = 2 * g_.a * (u * st - w * ct);
    if (std::abs(dh_dt) < 1e-12) return false;
    const Eigen::Vector3d dh_dq(2 * u, 2 * k * yf / root, 2 * w);
    const Eigen::Vector3d dt_dq = -dh_dq / dh_dt;
    // q = Rz(-phi) p + const, so dt/dp = dt/dq * Rz(-phi).
    dtheta_dp->row(i) << dt_dq.x() * cos_phi_[i] - dt_dq.y() * sin_phi_[i],
        dt_dq.x() * sin_phi_[i] + dt_dq.y() * cos_phi_[i], dt_dq.z();
  }
  return dtheta_dp->allFinite();
}

bool FalconKinematics::Forward(const Eigen::Vector3d& theta_rad, const Eigen::Vector3d& guess_m,
                               Eigen::Vector3d* p_m, int max_iterations) const {
  Eigen::Vector3d p = guess_m.allFinite() ? guess_m : FalconCentre();
  if (!theta_rad.allFinite()) {
    *p_m = p;
    return false;
  }
  // max_iterations Newton steps; the last pass only checks convergence.
  for (int it = 0; it <= max_iterations; ++it) {
    Eigen::Vector3d th;
    Eigen::Matrix3d jac;
    if (!Inverse(p, &th) || !AngleJacobian(p, &jac)) {
      // Left the reachable set: restart from the centre once.
      if (p != FalconCentre()) {
        p = FalconCentre();
        continue;
      }
      break;
    }
    const Eigen::Vector3d r = th - theta_rad;
    if (r.cwiseAbs().maxCoeff() < 1e-10) {
      *p_m = p;
      return true;
    }
    if (it == max_iterations) break;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(jac);
    if (!lu.isInvertible()) break;
    Eigen::Vector3d step = lu.solve(r);
    // Damp huge steps (a bad warm start) to stay in the reachable set.
    const double n = step.norm();
    if (n > 0.02) step *= 0.02 / n;
    p -= step;
  }
  *p_m = p;
  return false;
}

bool FalconKinematics::ForceToTorque(const Eigen::Vector3d& p_m, const Eigen::Vector3d& force_n,
                                     Eigen::Vector3d* torque_nm) const {
  Eigen::Matrix3d dtheta_dp;
  if (!force_n.allFinite() || !AngleJacobian(p_m, &dtheta_dp)) return false;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(dtheta_dp);
  if (!lu.isInvertible()) return false;
  // tau = J^T F with J = (dtheta/dp)^-1  <=>  (dtheta/dp)^T tau = F.
  const Eigen::Matrix3d jt = dtheta_dp.transpose();
  const Eigen::Vector3d tau = jt.fullPivLu().solve(force_n);
  if (!tau.allFinite()) return false;
  *torque_nm = tau;
  return true;
}

double TorqueCounts(const Eigen::Vector3d& torque_nm, double counts_per_nm,
                    Eigen::Vector3d* counts) {
  *counts = counts_per_nm * torque_nm;
  const double peak = counts->cwiseAbs().maxCoeff();
  if (!(peak > 32767.0)) return 1.0;
  const double scale = 32767.0 / peak;
  *counts *= scale;
  return scale;
}

}  // namespace hapcine
