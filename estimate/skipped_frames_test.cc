#include "estimate/skipped_frames.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rotation.h"

namespace hapcine {
namespace {

CameraFrame At(int index, double yaw_rad, double x, double focal, int shot = 0) {
  CameraFrame f;
  f.frame = index;
  f.time_s = index / 24.0;
  f.world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()));
  f.center = Eigen::Vector3d(x, 0, 0);
  f.focal_px = focal;
  f.fov_deg = FovDegFromFocalPx(focal, 1000);
  f.confidence = 0.9;
  f.shot = shot;
  f.model = "general+zoom";
  return f;
}

TEST(InsertSkippedFrames, BetweenNeighboursOfOneShot) {
  CameraPath path;
  path.frames = {At(0, 0.0, 0.0, 1000), At(3, 0.3, 3.0, 1331)};
  InsertSkippedFrames({{1, 1 / 24.0}, {2, 2 / 24.0}}, 1000, &path);
  ASSERT_EQ(path.frames.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(path.frames[i].frame, i);
  const CameraFrame& f = path.frames[1];  // a third of the way
  EXPECT_NEAR(f.time_s, 1 / 24.0, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(f.world_from_cam.quaternion()).angle(), 0.1, 1e-12);
  EXPECT_NEAR(f.center.x(), 1.0, 1e-12);
  EXPECT_NEAR(*f.focal_px, 1100, 1e-9);  // geometric: 1000 * 1.1
  EXPECT_FLOAT_EQ(f.fov_deg, FovDegFromFocalPx(1100, 1000));  // held as a float
  EXPECT_FLOAT_EQ(*f.confidence, kSkippedFrameConfidence * 0.9);
  EXPECT_EQ(f.model, "general+zoom");  // the later neighbour's interval
  EXPECT_TRUE(f.world_from_cam.coeffs().allFinite());
}

TEST(InsertSkippedFrames, LostAtTheEndsAndAcrossACut) {
  CameraPath path;
  path.frames = {At(1, 0.0, 0.0, 1000, 0), At(3, 0.2, 1.0, 1000, 1)};
  // 0 before any estimated frame, 2 between two shots, 4 and 5 after the last.
  InsertSkippedFrames({{0, 0.0}, {2, 2 / 24.0}, {4, 4 / 24.0}, {5, 5 / 24.0}}, 1000, &path);
  ASSERT_EQ(path.frames.size(), 6u);
  const int source[6] = {1, 1, 1, 3, 3, 3};  // whose pose each frame holds
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(path.frames[i].frame, i);
    const CameraFrame& from = path.frames[source[i]];
    EXPECT_EQ(path.frames[i].shot, from.shot) << i;
    EXPECT_EQ(path.frames[i].center, from.center) << i;
    EXPECT_LT(path.frames[i].world_from_cam.angularDistance(from.world_from_cam), 1e-15) << i;
    const bool skipped = i != 1 && i != 3;
    EXPECT_EQ(IsLost(path.frames[i]), skipped) << i;
    EXPECT_FLOAT_EQ(*path.frames[i].confidence, skipped ? 0.0 : 0.9) << i;
  }
}

// Next to a lost frame the motion on one side is unknown: not interpolated.
TEST(InsertSkippedFrames, LostNextToALostFrame) {
  CameraPath path;
  path.frames = {At(0, 0.0, 0.0, 1000), At(2, 0.0, 0.0, 1000), At(4, 0.4, 4.0, 1000), At(6, 0.6, 6.0, 1000)};
  path.frames[1].model = kLostModel;
  path.frames[1].confidence = 0;
  InsertSkippedFrames({{1, 1 / 24.0}, {3, 3 / 24.0}, {5, 5 / 24.0}}, 1000, &path);
  ASSERT_EQ(path.frames.size(), 7u);
  EXPECT_TRUE(IsLost(path.frames[1]));  // placed before, lost after
  EXPECT_TRUE(IsLost(path.frames[3]));  // lost before, placed after
  EXPECT_EQ(path.frames[3].center, path.frames[2].center);  // the placeholder held, no interpolation
  EXPECT_EQ(*path.frames[3].confidence, 0);
  EXPECT_FALSE(IsLost(path.frames[5]));  // between two placed frames
  EXPECT_NEAR(path.frames[5].center.x(), 5.0, 1e-12);
}

TEST(InsertSkippedFrames, IndicesAlreadyThereAndEmptyInputsChangeNothing) {
  CameraPath path;
  path.frames = {At(0, 0.0, 0.0, 1000), At(1, 0.1, 1.0, 1000)};
  InsertSkippedFrames({{1, 1 / 24.0}}, 1000, &path);
  ASSERT_EQ(path.frames.size(), 2u);
  EXPECT_NEAR(path.frames[1].center.x(), 1.0, 0);
  InsertSkippedFrames({}, 1000, &path);
  EXPECT_EQ(path.frames.size(), 2u);
  CameraPath empty;
  InsertSkippedFrames({{0, 0.0}}, 1000, &empty);
  EXPECT_TRUE(empty.frames.empty());
}

TEST(InsertSkippedFrames, FieldOfViewOnlyPathsAndEqualTimes) {
  CameraPath path;
  path.frames = {At(0, 0.0, 0.0, 1000), At(2, 0.2, 0.0, 1000)};
  for (auto& f : path.frames) f.focal_px.reset();
  path.frames[1].time_s = path.frames[0].time_s;  // a broken file's repeated time
  InsertSkippedFrames({{1, 0.0}}, 0, &path);
  ASSERT_EQ(path.frames.size(), 3u);
  EXPECT_FALSE(path.frames[1].focal_px);
  EXPECT_NEAR(path.frames[1].fov_deg, path.frames[0].fov_deg, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(path.frames[1].world_from_cam.quaternion()).angle(), 0.1, 1e-12);  // halfway
}

}  // namespace
}  // namespace hapcine
