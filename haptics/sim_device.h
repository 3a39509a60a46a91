#pragma once
// A simulated Falcon with a hand on it, so the player and the safety layer
// run and are tested without hardware.
//
// Model (seat frame, per axis, one rigid body because the hand holds the
// grip): (m_dev + m_hand) x'' = F_cmd - (b_dev + b_hand) x' - k_hand x
//   - F_coulomb tanh(x'/v0) + F_endstop(x).
// The device's links and motors are lumped into m_dev with viscous and
// Coulomb friction; the user's relaxed arm is the mass-spring-damper
// (m_hand, k_hand, b_hand) anchored at the workspace centre. Mechanical end
// stops are stiff walls at +-endstop_m. Integration is semi-implicit Euler
// with substeps: stable for walls up to 20 kN/m at 1 kHz.
//
// The force passes through the real Falcon path: J^T F -> torque counts
// (saturated to 16 bits) -> back to a Cartesian force, and the measured
// position passes through inverse kinematics, encoder quantisation and
// Newton forward kinematics, so sim numbers include those effects.
// Each Exchange() advances simulated time by dt_s: deterministic.

#include <Eigen/Core>

#include "haptics/device.h"
#include "haptics/falcon_kinematics.h"

namespace hapcine {

struct SimDeviceOptions {
  double dt_s = 0.001;                // simulated time per Exchange()
  int substeps = 10;                  // integration substeps per Exchange()
  double device_mass_kg = 0.15;       // lumped links + grip
  double device_viscous_n_s_m = 0.5;  // motor/link viscous friction
  double device_coulomb_n = 0.05;     // dry friction
  double hand_mass_kg = 0.35;         // the user's hand and forearm
  double hand_stiffness_n_m = 10;     // relaxed arm pulls towards the centre
  double hand_damping_n_s_m = 3;      // arm damping
  double endstop_m = 0.06;            // walls at +-endstop_m from the centre
  double endstop_stiffness_n_m = 20000;
  double max_force_n = 9.0;
  bool falcon_quantisation = true;  // encoders + 16-bit torques
  double counts_per_nm = -10000.0;  // as FalconDeviceOptions
  int homed_after_exchanges = 0;    // > 0: unhomed at first (tests)
  Eigen::Vector3d start_pos_m = Eigen::Vector3d::Zero();
  void Check() const;  // throws UsageError
};

class SimDevice : public Device {
 public:
  explicit SimDevice(SimDeviceOptions options = SimDeviceOptions());
  void Open() override { open_ = true; }
  void Close() noexcept override { open_ = false; }
  DeviceState Exchange(const Eigen::Vector3d& force_n) override;
  void SetLeds(uint8_t mask) noexcept override { leds_ = mask; }
  double MaxForceN() const override { return options_.max_force_n; }
  std::string Name() const override { return "sim"; }
  double LastSentForceN() const override { return last_force_n_.norm(); }

  // Ground truth, for tests.
  const Eigen::Vector3d& true_pos_m() const { return pos_m_; }
  const Eigen::Vector3d& true_vel_m_s() const { return vel_m_s_; }
  const Eigen::Vector3d& last_force_n() const { return last_force_n_; }  // as commanded
  double time_s() const { return time_s_; }
  // Pushes the grip (the user moving the hand), newtons, until changed.
  void set_external_force_n(const Eigen::Vector3d& f) { external_n_ = f; }

 private:
  Eigen::Vector3d RenderedForce(const Eigen::Vector3d& force_n) const;
  Eigen::Vector3d MeasuredPos() const;

  SimDeviceOptions options_;
  FalconKinematics kin_;
  bool open_ = false;
  uint8_t leds_ = 0;
  int exchanges_ = 0;
  double time_s_ = 0;
  Eigen::Vector3d pos_m_, vel_m_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d measured_prev_, vel_est_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d external_n_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_force_n_ = Eigen::Vector3d::Zero();
  mutable Eigen::Vector3d fk_guess_ = FalconCentre();
};

}  // namespace hapcine
