#pragma once
// Kinematics of a 6-6 Stewart platform (a hexapod): six legs of variable
// length join anchor points on a fixed base to anchor points on the moving
// top. Inverse kinematics is closed form: leg i = |p + R top_i - base_i|,
// with p and R = Rx(pitch) Ry(yaw) Rz(roll) from the pose (platform_config.h).
// Forward kinematics (legs -> pose) has no closed form; Newton iterations
// from the home pose solve it near home (used to check the inverse).

#include <array>
#include <optional>

#include "platform/platform_config.h"

namespace hapcine {

using LegLengths = std::array<double, 6>;

// R = Rx(pitch) Ry(yaw) Rz(roll) of a pose.
Eigen::Matrix3d PoseRotation(const PlatformPose& pose);

LegLengths StewartLegLengths(const StewartGeometry& g, const PlatformPose& pose);

// Whether every leg is within [min_leg + margin, max_leg - margin].
bool LegsWithinStroke(const StewartGeometry& g, const LegLengths& legs, double margin_m = 0);

// The pose whose legs are `legs`, by Newton iterations from `guess`
// (default home). nullopt when it does not converge to 1e-12 m.
std::optional<PlatformPose> StewartForwardKinematics(const StewartGeometry& g,
                                                     const LegLengths& legs,
                                                     const PlatformPose& guess = PlatformPose::Zero());

// The largest s in [0, 1] such that the legs of s * pose stay within the
// stroke shrunk by margin_m (bisection; the home pose must be inside).
double StrokeScale(const StewartGeometry& g, const PlatformPose& pose, double margin_m);

}  // namespace hapcine
