#pragma once
// Zero-phase smoothing of a camera path: removes jitter without lag.
// A Gaussian window is applied *symmetrically* around each sample (never a
// causal filter), so a ramp passes through unchanged and a step is blurred
// symmetrically but not delayed. Near the ends of a sequence the window
// shrinks to stay symmetric (radius = distance to the end), so the end
// samples are kept as they are and nothing is extrapolated.
// Rotations are averaged on the tangent space: q_i' = q_i exp(sum_k w_k log(q_i^-1 q_k)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace hapcine {

// sigma in samples; sigma <= 0 returns the input.
std::vector<double> SmoothScalars(const std::vector<double>& x, double sigma);
std::vector<Eigen::Vector3d> SmoothVectors(const std::vector<Eigen::Vector3d>& x, double sigma);
std::vector<Eigen::Quaterniond> SmoothRotations(const std::vector<Eigen::Quaterniond>& q, double sigma);

// Rotation vector (axis * angle, radians) of a unit quaternion, and back.
Eigen::Vector3d LogRotation(const Eigen::Quaterniond& q);
Eigen::Quaterniond ExpRotation(const Eigen::Vector3d& w);

}  // namespace hapcine
