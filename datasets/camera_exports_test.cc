#include "datasets/camera_exports.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

// A pan to the right: positive pan turns the view left, so the pan angle falls.
CameraPath PanRight(int frames, double step_deg, std::optional<int> shot = std::nullopt) {
  CameraPath p;
  p.metadata = {{"width", "1920"}, {"height", "1080"}, {"fps", "25"}};
  for (int i = 0; i < frames; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 25.0;
    f.world_from_cam = QuaternionFromPanTiltRoll({-step_deg * i, 0, 0});
    f.fov_deg = 60;
    f.shot = shot;
    p.frames.push_back(f);
  }
  return p;
}

// Two shots of 3 and 1 frames, each starting at the origin.
CameraPath TwoShots() {
  CameraPath p = PanRight(4, 2);
  for (int i = 0; i < 4; ++i) p.frames[i].shot = i < 3 ? 0 : 1;
  p.frames[3].world_from_cam = Eigen::Quaterniond::Identity();
  return p;
}

TEST(CameraExportsTest, SelectShotsSplitsAtCuts) {
  const auto shots = SelectShots(TwoShots(), std::nullopt, "in");
  ASSERT_EQ(shots.size(), 2u);
  EXPECT_EQ(shots[0].frames.size(), 3u);
  EXPECT_EQ(shots[1].shot, 1);
  ASSERT_EQ(shots[1].frames.size(), 1u);  // a shot of one frame is kept
  EXPECT_EQ(shots[1].frames[0].frame, 3);
  const auto only = SelectShots(TwoShots(), 1, "in");
  ASSERT_EQ(only.size(), 1u);
  EXPECT_EQ(only[0].shot, 1);
  // No shot column: the whole path is shot 0.
  EXPECT_EQ(SelectShots(PanRight(3, 1), std::nullopt, "in").size(), 1u);
}

TEST(CameraExportsTest, SelectShotsRefusesEmptyPathsAndAbsentShots) {
  try {
    SelectShots(CameraPath{}, std::nullopt, "in.camera.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "in.camera.csv: the camera path has no frames");
  }
  try {
    SelectShots(TwoShots(), 7, "in.camera.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "in.camera.csv: no frame of shot 7 (shots 0 to 1)");
  }
}

TEST(CameraExportsTest, PerShotFileNames) {
  EXPECT_EQ(PerShotFileName("out.txt", 3), "out.shot003.txt");
  EXPECT_EQ(PerShotFileName("dir.v2/out", 12), "dir.v2/out.shot012");
  EXPECT_EQ(PerShotFileName(".hidden", 0), ".hidden.shot000");
  EXPECT_EQ(PerShotFileName("a/b.c/film.chan", 1000), "a/b.c/film.shot1000.chan");
}

TEST(CameraExportsTest, FrameRateFromHeaderOrTimes) {
  CameraPath p = PanRight(5, 1);
  EXPECT_EQ(ExportFps(p), 25);
  p.metadata.clear();
  EXPECT_NEAR(ExportFps(p), 25, 1e-9);
  p.frames.resize(1);
  EXPECT_EQ(ExportFps(p), 24);  // one frame: no interval to measure
}

// ---- Nuke

TEST(CameraExportsTest, NukePanRightIsNegativeRotateY) {
  const auto shots = SelectShots(PanRight(3, 5), std::nullopt, "in");
  const auto rows = NukeChanRows(shots[0], 1080.0 / 1920, 1);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].frame, 1);
  EXPECT_EQ(rows[2].frame, 3);
  EXPECT_NEAR(rows[2].rotate_deg.y(), -10, 1e-9);  // about +Y, counter-clockwise from above
  EXPECT_NEAR(rows[2].rotate_deg.x(), 0, 1e-9);
  EXPECT_NEAR(rows[2].rotate_deg.z(), 0, 1e-9);
  // Horizontal 60 degrees on 16:9 -> vertical 2 atan(tan 30 * 9/16).
  EXPECT_NEAR(rows[0].vertical_fov_deg, 35.98339, 1e-4);
}

TEST(CameraExportsTest, NukeRotationOrderIsZxy) {
  // A frame turned by all three angles: R = R_y(ry) R_x(rx) R_z(rz).
  CameraPath p = PanRight(1, 0);
  p.frames[0].world_from_cam = QuaternionFromPanTiltRoll({30, 20, 10});
  const auto rows = NukeChanRows(SelectShots(p, std::nullopt, "in")[0], 0.5, 1);
  EXPECT_NEAR(rows[0].rotate_deg.x(), 20, 1e-9);
  EXPECT_NEAR(rows[0].rotate_deg.y(), 30, 1e-9);
  EXPECT_NEAR(rows[0].rotate_deg.z(), 10, 1e-9);
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(DegToRad(30), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(DegToRad(20), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(DegToRad(10), Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  EXPECT_TRUE(NukeRotation(rows[0].rotate_deg).toRotationMatrix().isApprox(expected, 1e-12));
}

TEST(CameraExportsTest, NukeAnglesDoNotJumpAcrossHalfTurn) {
  // A 400-degree pan right in 10-degree steps: rotate.y runs on to -400.
  const auto rows = NukeChanRows(SelectShots(PanRight(41, 10), std::nullopt, "in")[0], 0.5, 1);
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_NEAR(rows[i].rotate_deg.y() - rows[i - 1].rotate_deg.y(), -10, 1e-6) << i;
  }
  EXPECT_NEAR(rows.back().rotate_deg.y(), -400, 1e-6);
}

TEST(CameraExportsTest, NukeChanReadsBack) {
  CameraPath p = PanRight(4, 3);
  p.frames[2].center = {0.25, -1e-9, 3};
  const auto rows = NukeChanRows(SelectShots(p, std::nullopt, "in")[0], 0.75, 1001);
  std::stringstream s;
  WriteNukeChan(rows, s);
  const auto back = ReadNukeChan(s, "mem");
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].frame, 1001 + static_cast<int>(i));
    EXPECT_EQ(back[i].translate, p.frames[i].center);  // shortest exact decimals
    EXPECT_NEAR(AngleBetweenDeg(NukeRotation(back[i].rotate_deg), p.frames[i].world_from_cam), 0,
                1e-9);
    EXPECT_EQ(back[i].vertical_fov_deg, rows[i].vertical_fov_deg);
  }
}

TEST(CameraExportsTest, NukeChanReaderNamesTheBadLine) {
  std::istringstream s("1 0 0 0 0 0 0 40\n\n2 0 0 0 0 0 40\n");
  try {
    ReadNukeChan(s, "cam.chan");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "cam.chan:3: expected 8 values (frame tx ty tz rx ry rz vfov), got 7");
  }
}

// ---- KITTI

TEST(CameraExportsTest, KittiPanRightTurnsOpticalAxisToPlusX) {
  const auto poses = KittiPoses(SelectShots(PanRight(3, 5), std::nullopt, "in")[0]);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_TRUE(poses[0].isApprox(KittiPose::Identity(), 1e-15));
  // KITTI camera: z forward, x right. After a pan right the optical axis
  // (third column) leans to +x, and the camera's y (down) stays down.
  const Eigen::Vector3d forward = poses[2].col(2);
  EXPECT_NEAR(forward.x(), std::sin(DegToRad(10)), 1e-12);
  EXPECT_NEAR(forward.z(), std::cos(DegToRad(10)), 1e-12);
  EXPECT_NEAR(poses[2](1, 1), 1, 1e-12);
}

TEST(CameraExportsTest, KittiForwardTravelIsPlusZ) {
  CameraPath p = PanRight(2, 0);
  // The whole shot looks along world +X (pan -90) and moves 2 units that way.
  for (auto& f : p.frames) f.world_from_cam = QuaternionFromPanTiltRoll({-90, 0, 0});
  p.frames[0].center = {1, 0, 0};
  p.frames[1].center = {3, 0.5, 0};  // and 0.5 up
  const auto poses = KittiPoses(SelectShots(p, std::nullopt, "in")[0]);
  EXPECT_TRUE(poses[0].isApprox(KittiPose::Identity(), 1e-12));
  EXPECT_NEAR(poses[1](0, 3), 0, 1e-12);
  EXPECT_NEAR(poses[1](1, 3), -0.5, 1e-12);  // up is -y
  EXPECT_NEAR(poses[1](2, 3), 2, 1e-12);
}

TEST(CameraExportsTest, KittiReadsBack) {
  CameraPath p = PanRight(3, 7);
  p.frames[1].center = {0.1, 0.2, 0.3};
  const auto poses = KittiPoses(SelectShots(p, std::nullopt, "in")[0]);
  std::stringstream s;
  WriteKittiPoses(poses, s);
  const auto back = ReadKittiPoses(s, "mem");
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(back[i], poses[i]);
  std::string first_line = s.str().substr(0, s.str().find('\n'));
  EXPECT_EQ(first_line, "1 0 0 0 0 1 0 0 0 0 1 0");
}

// ---- Blender

TEST(CameraExportsTest, BlenderCameraLooksAlongPlusYWithZUp) {
  const BlenderPose pose = BlenderPoseFromFrame(PanRight(1, 0).frames[0]);
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  EXPECT_TRUE((-r.col(2)).isApprox(Eigen::Vector3d::UnitY(), 1e-12));  // view: -Z of the camera
  EXPECT_TRUE(r.col(1).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));     // image up
  CameraFrame f;
  f.center = {1, 2, 3};  // right, up, backward
  EXPECT_TRUE(BlenderPoseFromFrame(f).location.isApprox(Eigen::Vector3d(1, -3, 2), 1e-12));
}

TEST(CameraExportsTest, BlenderPanRightTurnsClockwiseAboutZ) {
  const BlenderPose pose = BlenderPoseFromFrame(PanRight(3, 5).frames[2]);
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d view = -r.col(2);
  EXPECT_NEAR(view.x(), std::sin(DegToRad(10)), 1e-12);  // towards +X (right)
  EXPECT_NEAR(view.y(), std::cos(DegToRad(10)), 1e-12);
  // Blender's XYZ Euler of this pose is (90, 0, -10): Z rotation negative.
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(DegToRad(-10), Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(DegToRad(90), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  EXPECT_TRUE(r.isApprox(expected, 1e-12));
}

TEST(CameraExportsTest, BlenderLensFromFov) {
  // 36 mm wide at 50 mm: 2 atan(18 / 50) = 39.5978 degrees.
  EXPECT_NEAR(LensMmFromFovDeg(RadToDeg(2 * std::atan(18.0 / 50)), 36), 50, 1e-9);
  EXPECT_NEAR(LensMmFromFovDeg(90, 24), 12, 1e-9);
}

TEST(CameraExportsTest, BlenderScriptHasOneCameraPerShot) {
  const CameraPath p = TwoShots();
  BlenderExportOptions o;
  o.source = "it's a\nfilm.mp4";
  std::stringstream s;
  WriteBlenderScript(p, SelectShots(p, std::nullopt, "in"), o, s);
  const std::string text = s.str();
  EXPECT_NE(text.find("SOURCE = 'it\\'s a\\x0afilm.mp4'\n"), std::string::npos);
  EXPECT_NE(text.find("FPS = 25\n"), std::string::npos);
  EXPECT_NE(text.find("WIDTH = 1920\nHEIGHT = 1080\n"), std::string::npos);
  EXPECT_NE(text.find("SENSOR_WIDTH_MM = 36\n"), std::string::npos);
  EXPECT_NE(text.find("(0, '''\n1 0 0 0 "), std::string::npos);  // frame 0 -> Blender 1
  EXPECT_NE(text.find("(1, '''\n4 0 0 0 "), std::string::npos);  // one-frame shot
  EXPECT_NE(text.find("\nmain()\n"), std::string::npos);
}

}  // namespace
}  // namespace hapcine
