#include "haptics/sim_device.h"

#include <Eigen/LU>
#include <cmath>

#include "core/error.h"
#include "haptics/falcon_protocol.h"

namespace hapcine {

void SimDeviceOptions::Check() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw UsageError(std::string("sim ") + name + " must be > 0");
  };
  auto nonneg = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v))
      throw UsageError(std::string("sim ") + name + " must be >= 0");
  };
  positive(dt_s, "dt_s");
  positive(device_mass_kg, "device_mass_kg");
  positive(endstop_m, "endstop_m");
  positive(max_force_n, "max_force_n");
  nonneg(device_viscous_n_s_m, "device_viscous_n_s_m");
  nonneg(device_coulomb_n, "device_coulomb_n");
  nonneg(hand_mass_kg, "hand_mass_kg");
  nonneg(hand_stiffness_n_m, "hand_stiffness_n_m");
  nonneg(hand_damping_n_s_m, "hand_damping_n_s_m");
  nonneg(endstop_stiffness_n_m, "endstop_stiffness_n_m");
  if (substeps < 1 || substeps > 1000) throw UsageError("sim substeps must be in [1, 1000]");
  if (!start_pos_m.allFinite()) throw UsageError("sim start_pos_m must be finite");
}

SimDevice::SimDevice(SimDeviceOptions options) : options_(options) {
  options_.Check();
  pos_m_ = options_.start_pos_m;
  measured_prev_ = pos_m_;
}

Eigen::Vector3d SimDevice::RenderedForce(const Eigen::Vector3d& force_n) const {
  if (!force_n.allFinite()) return Eigen::Vector3d::Zero();  // as the real device: no torque
  if (!options_.falcon_quantisation) return force_n;
  // Seat frame == Falcon frame here (front mount).
  const Eigen::Vector3d p = FalconCentre() + pos_m_;
  Eigen::Vector3d tau;
  Eigen::Matrix3d dtheta_dp;
  if (!kin_.ForceToTorque(p, force_n, &tau) || !kin_.AngleJacobian(p, &dtheta_dp))
    return Eigen::Vector3d::Zero();
  Eigen::Vector3d counts;
  TorqueCounts(tau, options_.counts_per_nm, &counts);  // as FalconDevice sends them
  for (int i = 0; i < 3; ++i) counts[i] = SaturateTorque(counts[i]);
  // F = (dtheta/dp)^T tau.
  return dtheta_dp.transpose() * (counts / options_.counts_per_nm);
}

Eigen::Vector3d SimDevice::MeasuredPos() const {
  if (!options_.falcon_quantisation) return pos_m_;
  Eigen::Vector3d theta;
  if (!kin_.Inverse(FalconCentre() + pos_m_, &theta)) return pos_m_;
  for (int i = 0; i < 3; ++i)
    theta[i] = EncoderToAngleRad(SaturateTorque(std::round(AngleRadToEncoder(theta[i]))));
  Eigen::Vector3d p;
  if (!kin_.Forward(theta, fk_guess_, &p)) return pos_m_;
  fk_guess_ = p;
  return p - FalconCentre();
}

DeviceState SimDevice::Exchange(const Eigen::Vector3d& force_n) {
  DeviceState s;
  if (!open_) {
    s.fault = DeviceFault::kNotOpen;
    return s;
  }
  ++exchanges_;
  const bool homed = exchanges_ > options_.homed_after_exchanges;
  last_force_n_ = force_n;
  const Eigen::Vector3d f_cmd = homed ? RenderedForce(force_n) : Eigen::Vector3d::Zero();
  const SimDeviceOptions& o = options_;
  const double m = o.device_mass_kg + o.hand_mass_kg;
  const double h = o.dt_s / o.substeps;
  for (int k = 0; k < o.substeps; ++k) {
    Eigen::Vector3d f = f_cmd + external_n_ -
                        (o.device_viscous_n_s_m + o.hand_damping_n_s_m) * vel_m_s_ -
                        o.hand_stiffness_n_m * pos_m_;
    for (int i = 0; i < 3; ++i) {
      f[i] -= o.device_coulomb_n * std::tanh(vel_m_s_[i] / 1e-3);
      const double over = std::abs(pos_m_[i]) - o.endstop_m;
      if (over > 0)
        f[i] -= std::copysign(o.endstop_stiffness_n_m * over, pos_m_[i]) + 20.0 * vel_m_s_[i];
    }
    vel_m_s_ += h * f / m;
    pos_m_ += h * vel_m_s_;
  }
  time_s_ += o.dt_s;
  const Eigen::Vector3d measured = MeasuredPos();
  // Velocity as a real driver gets it: differentiated, low-passed (60 Hz).
  const double alpha = 1.0 - std::exp(-2 * M_PI * 60.0 * o.dt_s);
  vel_est_ += alpha * ((measured - measured_prev_) / o.dt_s - vel_est_);
  measured_prev_ = measured;
  s.pos_m = measured;
  s.vel_m_s = vel_est_;
  s.homed = homed;
  return s;
}

}  // namespace hapcine
