#pragma once
// Kinematics of the Novint Falcon, a 3-DOF parallel delta robot, after R. E.
// Stamper's analysis (the geometry constants of novint-falcon.md).
//
// Falcon frame: the frame of the device itself, metres, origin near the
// motors, +z out of the device towards the user. The reachable region is
// roughly x, y in [-0.06, 0.06] and z in [0.075, 0.175]; the notes' 0.06 m
// cube around kFalconCentre is where the grip moves freely.
//
// Each leg i has one actuated angle theta1_i (the motor arm, radians) and two
// passive angles. A leg lives in its own frame: the end-effector point p
// rotated by Rz(-phi_i) then offset by (-r, -s, 0). In that frame
//   p_leg = (a cos t1 - c + K cos t2,  b cos t3 - f,  a sin t1 + K sin t2),
//   K = d + e + b sin t3,
// so the leg's closure constraint, free of the passive t2, is
//   h(p_leg, t1) = (x - a cos t1 + c)^2 + (z - a sin t1)^2 - K(y)^2 = 0,
//   K(y) = d + e + sqrt(b^2 - (y + f)^2).
// Inverse kinematics solves h = 0 for t1 (a quadratic in tan(t1/2));
// forward kinematics runs Newton-Raphson on the inverse; the Jacobian comes
// from differentiating h implicitly (see falcon_kinematics.cc).
//
// Nothing here allocates: safe in the 1 kHz tick.

#include <Eigen/Core>
#include <cstdint>

namespace hapcine {

struct FalconGeometry {
  double a = 0.060, b = 0.1025, c = 0.01443, d = 0.01125, e = 0.01125;
  double f = -0.025, r = 0.0400, s = -0.02309;
  double phi_deg[3] = {105.0, -15.0, -135.0};  // leg angles about z
};

// Centre of the Falcon's free workspace, Falcon frame (metres).
inline Eigen::Vector3d FalconCentre() { return Eigen::Vector3d(0, 0, 0.125); }

// Encoder counts <-> motor-arm angle theta1. 320 slots x 4 quadrature edges,
// 14.25 mm shaft on a 110 mm drum: 360/1280 * 14.25/110 = 0.036435 deg/count,
// offset 35 deg at count 0.
constexpr double kFalconDegPerCount = 0.036435;
constexpr double kFalconAngleOffsetDeg = 35.0;
double EncoderToAngleRad(int16_t counts);
double AngleRadToEncoder(double theta1_rad);  // not rounded; for tests/sim

// Motor command counts for arm torques: counts_per_nm * tau, all three
// scaled together when the largest exceeds 16 bits (near a singularity a
// modest force can need that), so the force keeps its direction; clipping
// one motor alone would push another way. Returns the scale (<= 1).
double TorqueCounts(const Eigen::Vector3d& torque_nm, double counts_per_nm,
                    Eigen::Vector3d* counts);

class FalconKinematics {
 public:
  explicit FalconKinematics(const FalconGeometry& g = FalconGeometry());

  // p (Falcon frame) -> theta1 of the three legs. False if p is unreachable
  // (outside the acos / square-root domains); *theta_rad untouched then.
  bool Inverse(const Eigen::Vector3d& p_m, Eigen::Vector3d* theta_rad) const;

  // theta1 of the three legs -> p, by Newton-Raphson on Inverse() started at
  // `guess_m` (warm start: the previous position). Converges to |dtheta| <
  // 1e-10 rad in a few iterations near the previous position. False if it
  // did not converge in max_iterations; *p_m then holds the last iterate.
  bool Forward(const Eigen::Vector3d& theta_rad, const Eigen::Vector3d& guess_m,
               Eigen::Vector3d* p_m, int max_iterations = 15) const;

  // d theta / d p at p (row i: gradient of leg i's theta1). False where the
  // leg is singular (d h / d theta1 ~ 0) or p unreachable.
  bool AngleJacobian(const Eigen::Vector3d& p_m, Eigen::Matrix3d* dtheta_dp) const;

  // Motor-arm torques (N m, one per leg) that render the Cartesian force
  // `force_n` at p: tau = J^T F with J = dp/dtheta = (dtheta/dp)^-1, i.e. the
  // virtual-work identity tau . dtheta = F . dp. False near singularities.
  bool ForceToTorque(const Eigen::Vector3d& p_m, const Eigen::Vector3d& force_n,
                     Eigen::Vector3d* torque_nm) const;

  const FalconGeometry& geometry() const { return g_; }

 private:
  // Leg-frame point of leg i.
  Eigen::Vector3d ToLeg(int leg, const Eigen::Vector3d& p_m) const;
  FalconGeometry g_;
  double cos_phi_[3], sin_phi_[3];
};

}  // namespace hapcine
