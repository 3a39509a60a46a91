#include "bench/peer_convert.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rotation.h"

namespace hapcine::bench {
namespace {

// A similarity (pixels, y down) about the image centre: scale s, content
// rotation a (rad), then a shift (dx, dy).
Eigen::Matrix3d Similarity(double w, double h, double s, double a, double dx, double dy) {
  Eigen::Matrix3d to_c = Eigen::Matrix3d::Identity(), from_c = Eigen::Matrix3d::Identity(), m = Eigen::Matrix3d::Identity();
  to_c(0, 2) = -w / 2;
  to_c(1, 2) = -h / 2;
  from_c(0, 2) = w / 2;
  from_c(1, 2) = h / 2;
  m << s * std::cos(a), -s * std::sin(a), dx, s * std::sin(a), s * std::cos(a), dy, 0, 0, 1;
  return from_c * m * to_c;
}

TEST(CameraFromSimilarity, IdentityIsTheStartingCamera) {
  const SimilarityCamera c = CameraFromSimilarity(Eigen::Matrix3d::Identity(), 640, 360, 700);
  EXPECT_DOUBLE_EQ(c.focal_px, 700);
  EXPECT_NEAR(c.pan_deg, 0, 1e-12);
  EXPECT_NEAR(c.tilt_deg, 0, 1e-12);
  EXPECT_NEAR(c.roll_deg, 0, 1e-12);
}

TEST(CameraFromSimilarity, SignsFollowTheSpec) {
  // Content moving right and down: the view turned left (pan > 0) and up (tilt > 0).
  SimilarityCamera c = CameraFromSimilarity(Similarity(640, 360, 1, 0, 700 * std::tan(DegToRad(5)), 0), 640, 360, 700);
  EXPECT_NEAR(c.pan_deg, 5, 1e-9);
  c = CameraFromSimilarity(Similarity(640, 360, 1, 0, 0, 700 * std::tan(DegToRad(3))), 640, 360, 700);
  EXPECT_NEAR(c.tilt_deg, 3, 1e-9);
  // Content turning clockwise on screen (positive angle with y down): positive roll.
  c = CameraFromSimilarity(Similarity(640, 360, 1, DegToRad(10), 0, 0), 640, 360, 700);
  EXPECT_NEAR(c.roll_deg, 10, 1e-9);
  EXPECT_NEAR(c.pan_deg, 0, 1e-9);
  // Content growing: zoom in, longer focal.
  c = CameraFromSimilarity(Similarity(640, 360, 1.5, 0, 0, 0), 640, 360, 700);
  EXPECT_NEAR(c.focal_px, 1050, 1e-9);
}

TEST(RelativeRotationGl, PanInOpenCvAxesIsPanInTheFile) {
  // A camera turned left by 10 deg: in OpenCV axes (Y down) that is a rotation
  // about +Y by -10 deg; in the file's axes (Y up) about +Y by +10 deg.
  const Eigen::Matrix3d first = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d turned = Eigen::AngleAxisd(DegToRad(-10), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const PanTiltRoll ptr = PanTiltRollFromQuaternion(RelativeRotationGl(first, turned));
  EXPECT_NEAR(ptr.pan_deg, 10, 1e-9);
  EXPECT_NEAR(ptr.tilt_deg, 0, 1e-9);
  // Relative to an arbitrary first camera: the same answer.
  const Eigen::Matrix3d base = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(AngleBetweenDeg(RelativeRotationGl(base, base * turned), RelativeRotationGl(first, turned)), 0, 1e-9);
}

TEST(InterpolateFrames, MidpointOfRotationAndFocal) {
  CameraFrame a, b;
  a.time_s = 0;
  b.time_s = 1;
  a.focal_px = 500;
  b.focal_px = 2000;
  a.fov_deg = FovDegFromFocalPx(500, 640);
  b.fov_deg = FovDegFromFocalPx(2000, 640);
  b.world_from_cam = QuaternionFromPanTiltRoll({20, 0, 0});
  const CameraFrame m = InterpolateFrames(a, b, 0.5);
  EXPECT_NEAR(*m.focal_px, 1000, 1e-9);
  EXPECT_FLOAT_EQ(m.fov_deg, FovDegFromFocalPx(1000, 640));  // held as a float
  EXPECT_NEAR(PanTiltRollFromQuaternion(m.world_from_cam).pan_deg, 10, 1e-9);
  EXPECT_NEAR(m.time_s, 0.5, 1e-12);
}

}  // namespace
}  // namespace hapcine::bench
