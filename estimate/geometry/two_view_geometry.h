#pragma once
// Maths on finished two-view models (estimation is in two_view_estimators.h).
// Same conventions: OpenCV camera frame, cam2_from_cam1, normalised
// coordinates u = (pixel - centre) / s, calibrated coordinates u / f.

#include <Eigen/Core>
#include <vector>

namespace hapcine {

// Relative pose from an essential matrix: of the four (R, t) choices, the one
// that puts most of the given correspondences in front of both cameras.
// t is a unit vector (X2 = R X1 + t). Returns false if no choice has a
// majority in front (degenerate or pure rotation).
bool DecomposeEssential(const Eigen::Matrix3d& E, const std::vector<Eigen::Vector2d>& c1,
                        const std::vector<Eigen::Vector2d>& c2, Eigen::Matrix3d* cam2_from_cam1,
                        Eigen::Vector3d* t);

// Least-squares rotation between two sets of calibrated coordinates (Kabsch).
bool FitRotation(const std::vector<Eigen::Vector2d>& c1, const std::vector<Eigen::Vector2d>& c2,
                 Eigen::Matrix3d* cam2_from_cam1);

// Pure rotation with one unknown focal f shared by both views: minimises the
// reprojection error in normalised units over log f in [f0 / range, f0 * range]
// (golden section), fitting R by Kabsch at each f. Returns the sum of squared
// residuals; `f` and `R` receive the optimum.
double FitRotationAndFocal(const std::vector<Eigen::Vector2d>& u1,
                           const std::vector<Eigen::Vector2d>& u2, double f0, double range,
                           double* f, Eigen::Matrix3d* cam2_from_cam1);

// Rotation with view 1's focal f1 known and view 2's focal free.
double FitRotationZoom(const std::vector<Eigen::Vector2d>& u1,
                       const std::vector<Eigen::Vector2d>& u2, double f1, double f2_0, double range,
                       double* f2, Eigen::Matrix3d* cam2_from_cam1);

// Depth along ray 1 of the point closest to both rays (midpoint method), in
// camera 1's frame, X2 = R X1 + t. Returns <= 0 or NaN-free large values for
// (near-)parallel rays; callers treat depth <= 0 as "at infinity".
double TriangulateDepth(const Eigen::Vector2d& c1, const Eigen::Vector2d& c2,
                        const Eigen::Matrix3d& cam2_from_cam1, const Eigen::Vector3d& t);

}  // namespace hapcine
