#include "core/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

CameraPath MakePath(int n) {
  CameraPath p;
  p.metadata["width"] = "1280";
  p.metadata["height"] = "720";
  p.metadata["fps"] = "24";
  for (int i = 0; i < n; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 24.0;
    f.center = {0.01 * i, -0.002 * i, 0.5 - 0.03 * i};
    f.world_from_cam = QuaternionFromPanTiltRoll({1.5 * i, -0.7 * i, 0.3 * i});
    f.fov_deg = 55 + 0.1 * i;
    f.focal_px = FocalPxFromFovDeg(f.fov_deg, 1280);
    f.shot = i / 5;
    f.model = i < 5 ? "rotation" : "general";
    f.confidence = 0.9;
    p.frames.push_back(f);
  }
  return p;
}

TEST(CameraPathTest, RoundTripKeepsEveryValue) {
  const CameraPath p = MakePath(12);
  std::stringstream ss;
  WriteCameraPath(p, ss);
  const CameraPath q = ReadCameraPath(ss, "mem");
  ASSERT_EQ(q.frames.size(), p.frames.size());
  EXPECT_EQ(q.width(), 1280);
  EXPECT_EQ(q.height(), 720);
  EXPECT_DOUBLE_EQ(q.fps(), 24);
  for (size_t i = 0; i < p.frames.size(); ++i) {
    EXPECT_EQ(q.frames[i].frame, p.frames[i].frame);
    EXPECT_NEAR(q.frames[i].time_s, p.frames[i].time_s, 1e-6);
    EXPECT_TRUE(q.frames[i].center.isApprox(p.frames[i].center, 1e-15));
    EXPECT_LT(AngleBetweenDeg(q.frames[i].world_from_cam, p.frames[i].world_from_cam), 1e-9);
    EXPECT_DOUBLE_EQ(q.frames[i].fov_deg, p.frames[i].fov_deg);
    EXPECT_DOUBLE_EQ(*q.frames[i].focal_px, *p.frames[i].focal_px);
    EXPECT_EQ(*q.frames[i].shot, *p.frames[i].shot);
    EXPECT_EQ(*q.frames[i].model, *p.frames[i].model);
    EXPECT_EQ(*q.frames[i].confidence, *p.frames[i].confidence);  // 0.9 as a float, as written
  }
}

// Fixed notation of a large time has over a hundred digits: written whole, it
// reads back as the same double (a fixed-size buffer once cut it).
TEST(CameraPathTest, HugeTimesRoundTripExactly) {
  CameraPath p = MakePath(3);
  for (size_t i = 0; i < p.frames.size(); ++i) p.frames[i].time_s = 1e100 * (1 + i);
  std::stringstream ss;
  WriteCameraPath(p, ss);
  const CameraPath q = ReadCameraPath(ss, "huge.camera.csv");
  ASSERT_EQ(q.frames.size(), 3u);
  for (size_t i = 0; i < q.frames.size(); ++i) EXPECT_EQ(q.frames[i].time_s, p.frames[i].time_s);
}

TEST(CameraPathTest, ReadsTheSpecExample) {
  std::stringstream ss(
      "# width=1920 height=1080 fps=24\n"
      "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,focal_px,shot,model,confidence\n"
      "0,0.000000,0,0,0,1,0,0,0,55.000000,1843.92,0,rotation,0.97\n"
      "1,0.041667,0,0,0,0.99999,0,0.00436,0,55.000000,1843.92,0,rotation,0.97\n");
  const CameraPath p = ReadCameraPath(ss, "example");
  ASSERT_EQ(p.frames.size(), 2u);
  EXPECT_EQ(p.width(), 1920);
  EXPECT_EQ(p.height(), 1080);
  EXPECT_NEAR(PanTiltRollFromQuaternion(p.frames[1].world_from_cam).pan_deg, 0.4996, 1e-3);
}

TEST(CameraPathTest, WrittenAnglesFollowTheSpecConvention) {
  // Positive pan turns the view left: the optical axis (-Z) swings towards -X.
  const Eigen::Quaterniond q = QuaternionFromPanTiltRoll({10, 0, 0});
  const Eigen::Vector3d look = q * Eigen::Vector3d(0, 0, -1);
  EXPECT_LT(look.x(), 0);
  // Positive tilt turns the view up.
  EXPECT_GT((QuaternionFromPanTiltRoll({0, 10, 0}) * Eigen::Vector3d(0, 0, -1)).y(), 0);
  // Positive roll: the camera's +X axis tips upwards (counter-clockwise).
  EXPECT_GT((QuaternionFromPanTiltRoll({0, 0, 10}) * Eigen::Vector3d(1, 0, 0)).y(), 0);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* reason;  // substring of the message
  int line;
};

class CameraPathBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(CameraPathBadInputTest, RejectsWithLineAndReason) {
  const BadCase& c = GetParam();
  std::stringstream ss(c.text);
  try {
    ReadCameraPath(ss, "bad.camera.csv");
    FAIL() << "accepted " << c.name;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.camera.csv:" + std::to_string(c.line) + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.reason), std::string::npos) << msg;
  }
}

#define HDR "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n"
INSTANTIATE_TEST_SUITE_P(
    Malformed, CameraPathBadInputTest,
    ::testing::Values(
        BadCase{"empty", "", "no header", 0},
        BadCase{"wrong header", "frame,t,x,y,z,qw,qx,qy,qz,fov_deg\n0,0,0,0,0,1,0,0,0,50\n",
                "expected 'time_s'", 1},
        BadCase{"missing column", "frame,time_s,x,y,z,qw,qx,qy,qz\n", "missing column 'fov_deg'", 1},
        BadCase{"nan", HDR "0,0,nan,0,0,1,0,0,0,50\n", "non-finite", 2},
        BadCase{"inf", HDR "0,0,0,0,0,1,0,0,0,inf\n", "non-finite", 2},
        BadCase{"text", HDR "0,0,0,abc,0,1,0,0,0,50\n", "not a number", 2},
        BadCase{"truncated", HDR "0,0,0,0,0,1,0,0,0,50\n1,0.04,0,0\n", "truncated", 3},
        BadCase{"time backwards", HDR "0,0.1,0,0,0,1,0,0,0,50\n1,0.05,0,0,0,1,0,0,0,50\n",
                "not increasing", 3},
        BadCase{"non-unit quaternion", HDR "0,0,0,0,0,0.5,0,0,0,50\n", "unit length", 2},
        BadCase{"fov", HDR "0,0,0,0,0,1,0,0,0,0\n", "outside (0, 180)", 2},
        BadCase{"no rows", "# fps=24\n" HDR, "no data rows", 2},
        BadCase{"huge int", HDR "99999999999,0,0,0,0,1,0,0,0,50\n", "not an integer", 2},
        BadCase{"shot sentinel", "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,shot\n0,0,0,0,0,1,0,0,0,50,-2147483648\n",
                "not an integer", 2},  // the one int OptionalInt cannot hold
        BadCase{"nan focal", "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,focal_px\n0,0,0,0,0,1,0,0,0,50,nan\n",
                "non-finite", 2},
        BadCase{"focal beyond float", "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,focal_px\n0,0,0,0,0,1,0,0,0,50,1e39\n",
                "focal_px must be positive and finite", 2},
        BadCase{"nan confidence", "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,confidence\n0,0,0,0,0,1,0,0,0,50,nan\n",
                "non-finite", 2}),
    [](const auto& info) {
      std::string n = info.param.name;
      for (char& ch : n) if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(CameraPathTest, MetadataWithLineBreaksAndSeparatorsRoundTrips) {
  CameraPath p = MakePath(3);
  const std::string odd = std::string("film\nname\r,a=b\\c\x01\x1f\x7f é 日本 .mp4");
  p.metadata["source"] = odd;
  p.metadata["note"] = " leading and trailing ";
  std::stringstream ss;
  WriteCameraPath(p, ss);
  const CameraPath r = ReadCameraPath(ss, "mem");
  EXPECT_EQ(r.metadata.at("source"), odd);
  EXPECT_EQ(r.metadata.at("note"), " leading and trailing ");
  EXPECT_EQ(r.metadata.at("width"), "1280");
  ASSERT_EQ(r.frames.size(), 3u);
}

TEST(CameraPathTest, HeaderWithABackslashThatIsNoEscapeReadsAsWritten) {
  std::istringstream in(
      "# source=C:\\\\films\\\\a.mp4\n"  // as written now
      "# other=C:\\films\\a.mp4\n"           // as older versions wrote it
      "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n0,0,0,0,0,1,0,0,0,60\n");
  const CameraPath r = ReadCameraPath(in, "mem");
  EXPECT_EQ(r.metadata.at("source"), "C:\\films\\a.mp4");
  EXPECT_EQ(r.metadata.at("other"), "C:\\films\\a.mp4");
}

TEST(CameraPathTest, WriterRefusesNonFinite) {
  CameraPath p = MakePath(2);
  p.frames[1].center.x() = std::numeric_limits<double>::quiet_NaN();
  std::stringstream ss;
  EXPECT_THROW(WriteCameraPath(p, ss), Error);
}

// Values held at single precision print as the shortest text of that float,
// so a written file read and written again is the same text, byte for byte.
TEST(CameraPathTest, WrittenFileRoundTripsToTheSameText) {
  CameraPath p = MakePath(12);
  p.frames[3].fov_deg = FovDegFromFocalPx(1234.56789012345, 1280);  // a computed value
  p.frames[2].world_from_cam = QuaternionFromPanTiltRoll({90, 0, 0});  // qw = qy
  p.frames[4].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(kPi - 1e-9, Eigen::Vector3d(0.6, 0, 0.8)));
  p.frames[5].focal_px.reset();
  p.frames[6].shot = std::nullopt;
  p.frames[7].confidence = 0.123456789;
  std::stringstream first;
  WriteCameraPath(p, first);
  std::stringstream in(first.str()), second;
  WriteCameraPath(ReadCameraPath(in, "mem"), second);
  EXPECT_EQ(second.str(), first.str());
}

TEST(CameraPathTest, MinimalRowsReadBackAsWritten) {
  const std::string text =
      "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n"
      "0,0.000000,0,0,0.5,1,0,0,0,60\n"
      "1,0.041667,0,0,0.25,1,0,0,0,55.3\n";
  std::stringstream in(text);
  const CameraPath p = ReadCameraPath(in, "mem");
  ASSERT_EQ(p.frames.size(), 2u);
  EXPECT_FALSE(p.frames[0].focal_px || p.frames[0].shot || p.frames[0].model || p.frames[0].confidence);
  EXPECT_EQ(p.frames[1].fov_deg, double(55.3f));
  std::stringstream out;
  WriteCameraPath(p, out);
  EXPECT_NE(out.str().find("\n1,0.041667,0,0,0.25,1,0,0,0,55.3,"), std::string::npos) << out.str();
}

// Rotations near a half turn (qw ~ 0) keep their angle: the stored form
// recomputes the largest coefficient, never qw from the other three.
TEST(CameraPathTest, HalfTurnsRoundTripExactly) {
  CameraPath p = MakePath(4);
  const double off_rad[] = {0, 1e-12, 1e-9, 1e-6};
  for (int i = 0; i < 4; ++i) {
    p.frames[i].world_from_cam =
        Eigen::Quaterniond(Eigen::AngleAxisd(kPi - off_rad[i], Eigen::Vector3d(0, 1, 0)));
  }
  std::stringstream ss;
  WriteCameraPath(p, ss);
  const CameraPath q = ReadCameraPath(ss, "mem");
  for (int i = 0; i < 4; ++i) {
    const Eigen::Quaterniond r = q.frames[i].world_from_cam;
    EXPECT_GE(r.w(), 0);
    EXPECT_EQ(r.w(), p.frames[i].world_from_cam.w()) << i;  // about sin(off / 2)
    EXPECT_LT(AngleBetweenDeg(r, p.frames[i].world_from_cam), 1e-12) << i;
  }
}

TEST(CameraPathTest, ShotsKeepTheirWholeRange) {
  CameraPath p = MakePath(3);
  p.frames[0].shot = -1;
  p.frames[1].shot = std::numeric_limits<int>::min() + 1;
  p.frames[2].shot = std::numeric_limits<int>::max();
  std::stringstream ss;
  WriteCameraPath(p, ss);
  const CameraPath q = ReadCameraPath(ss, "mem");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(q.frames[i].shot, p.frames[i].shot) << i;
}

TEST(CameraPathTest, WriterRefusesNaNOptionalValues) {
  for (int field = 0; field < 2; ++field) {
    CameraPath p = MakePath(2);
    OptionalFloat& v = field == 0 ? p.frames[1].focal_px : p.frames[1].confidence;
    v = std::numeric_limits<double>::quiet_NaN();
    std::stringstream ss;
    EXPECT_THROW(WriteCameraPath(p, ss), Error) << field;
  }
}

TEST(CameraPathTest, WriterRefusesANonUnitQuaternionWithItsNorm) {
  CameraPath p = MakePath(2);
  p.frames[1].world_from_cam = Eigen::Quaterniond(2, 0, 0, 0);
  std::stringstream ss;
  try {
    WriteCameraPath(p, ss);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not unit length (|q| = 2)"), std::string::npos) << e.what();
  }
}

TEST(CameraPathTest, FailedFileWriteLeavesNothing) {
  CameraPath p = MakePath(2);
  p.frames[1].fov_deg = -1;
  const std::string file = ::testing::TempDir() + "/bad_write.camera.csv";
  EXPECT_THROW(WriteCameraPathFile(p, file), Error);
  EXPECT_FALSE(std::ifstream(file).good());
}

// An image sequence's frame numbers (plate.1001.exr) ride in the optional
// `source_frame` column; a path without them has no such column.
TEST(CameraPathTest, SourceFrameColumnIsOptional) {
  CameraPath p = MakePath(3);
  std::stringstream plain;
  WriteCameraPath(p, plain);
  EXPECT_EQ(plain.str().find("source_frame"), std::string::npos);
  for (const CameraFrame& f : p.frames) p.source_frames.push_back(1001 + f.frame);
  p.source_frames[1].reset();  // a frame without one: an empty cell
  std::stringstream ss;
  WriteCameraPath(p, ss);
  EXPECT_NE(ss.str().find(",confidence,source_frame\n"), std::string::npos) << ss.str();
  const CameraPath q = ReadCameraPath(ss, "mem");
  ASSERT_EQ(q.frames.size(), 3u);
  ASSERT_EQ(q.source_frames.size(), 3u);
  EXPECT_EQ(q.source_frames[0], 1001);
  EXPECT_FALSE(q.source_frames[1].has_value());
  EXPECT_EQ(q.source_frames[2], 1003);
  std::stringstream again(plain.str());
  EXPECT_TRUE(ReadCameraPath(again, "mem").source_frames.empty());
  // Numbers for some frames only cannot be written: which frames they belong to is unknown.
  p.source_frames.pop_back();
  std::stringstream bad;
  EXPECT_THROW(WriteCameraPath(p, bad), Error);
}

}  // namespace
}  // namespace hapcine
