#pragma once
// Rotation conventions of the camera path (docs/formats.md), in one place.
//   world_from_cam = R_y(pan) * R_x(tilt) * R_z(roll)   (angles in degrees)
// Positive pan turns the view left, positive tilt turns it up, positive roll
// turns the camera counter-clockwise. Euler angles are for people and for the
// haptic models only; nothing inside an optimiser uses them.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hapcine {

struct PanTiltRoll {
  double pan_deg = 0;   // about +Y
  double tilt_deg = 0;  // about +X
  double roll_deg = 0;  // about +Z
};

constexpr double kPi = 3.14159265358979323846;
inline double DegToRad(double deg) { return deg * kPi / 180.0; }
inline double RadToDeg(double rad) { return rad * 180.0 / kPi; }

Eigen::Quaterniond QuaternionFromPanTiltRoll(const PanTiltRoll& angles);
// Inverse of the above; at tilt = +-90 degrees pan and roll are not unique and
// the split puts everything into pan.
PanTiltRoll PanTiltRollFromQuaternion(const Eigen::Quaterniond& world_from_cam);

// Unit quaternion with qw >= 0 (the file convention).
Eigen::Quaterniond CanonicalQuaternion(const Eigen::Quaterniond& q);

// Angle of the relative rotation a^-1 b, in degrees, in [0, 180].
double AngleBetweenDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// Angle between the optical axes (+Z of each camera) of a and b, in degrees:
// roll about the axis does not count (it does not tell a focal length).
double OpticalAxisAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// Horizontal field of view <-> focal length in pixels for an image `width_px` wide.
double FovDegFromFocalPx(double focal_px, double width_px);
double FocalPxFromFovDeg(double fov_deg, double width_px);

}  // namespace hapcine
