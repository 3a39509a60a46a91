#include "datasets/tum_format.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

CameraPath SamplePath() {
  CameraPath p;
  for (int i = 0; i < 5; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 30.0;
    f.center = {0.1 * i, -0.2 * i, 1e-9 * i};
    f.world_from_cam = QuaternionFromPanTiltRoll({10.0 * i, -3.0 * i, 1.5 * i});
    f.fov_deg = 50;
    p.frames.push_back(f);
  }
  return p;
}

TEST(TumFormatTest, RoundTripKeepsPoses) {
  const CameraPath path = SamplePath();
  std::stringstream s;
  WriteTumTrajectory(path, s);
  const auto poses = ReadTumTrajectory(s, "mem");
  ASSERT_EQ(poses.size(), 5u);
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(poses[i].time_s, path.frames[i].time_s, 1e-6);
    EXPECT_EQ(poses[i].center, path.frames[i].center);  // shortest exact decimal
    EXPECT_NEAR(AngleBetweenDeg(poses[i].world_from_cam, path.frames[i].world_from_cam), 0,
                1e-9);
  }
  const CameraPath back = CameraPathFromTum(poses, 50);
  EXPECT_EQ(back.frames.size(), 5u);
  EXPECT_EQ(back.frames[3].frame, 3);
}

TEST(TumFormatTest, QuaternionIsScalarLast) {
  CameraPath p;
  CameraFrame f;
  f.world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()));
  f.fov_deg = 60;
  p.frames.push_back(f);
  std::stringstream s;
  WriteTumTrajectory(p, s);
  std::string comment, line;
  std::getline(s, comment);
  std::getline(s, line);
  EXPECT_EQ(comment[0], '#');
  std::istringstream fields(line);
  double v[8];
  for (double& x : v) fields >> x;
  EXPECT_NEAR(v[5], std::sqrt(0.5), 1e-12);  // qy
  EXPECT_NEAR(v[7], std::sqrt(0.5), 1e-12);  // qw
  EXPECT_NEAR(v[4], 0, 1e-12);
}

TEST(TumFormatTest, ReadsCommentsAndTabs) {
  std::istringstream s("# evo file\n\n1.0\t0 0 0 0 0 0 1\n2.0 1 2 3 0 0 0 1\n");
  const auto poses = ReadTumTrajectory(s, "mem");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[1].center, Eigen::Vector3d(1, 2, 3));
}

TEST(TumFormatTest, BadInputNamesTheLine) {
  auto expect_error = [](const std::string& text, const std::string& fragment) {
    std::istringstream s(text);
    try {
      ReadTumTrajectory(s, "t.txt");
      ADD_FAILURE() << "no error for: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("", "no poses");
  expect_error("1 0 0 0 0 0 0\n", "t.txt:1: expected 8 values");
  expect_error("1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", "t.txt:2: timestamp is not increasing");
  expect_error("1 0 0 0 0 0 0 2\n", "not unit");
  expect_error("1 0 0 x 0 0 0 1\n", "not a number");
  expect_error("1 0 0 nan 0 0 0 1\n", "non-finite");
}

// Not a regular file: refused with one line, never read (/dev/zero never
// ends; a directory used to read as an empty file).
TEST(TumFormatTest, RefusesWhatIsNotARegularFile) {
  const std::string dir = HAPCINE_BINARY_DIR;
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    try {
      ReadTumTrajectoryFile(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad + (bad == dir ? ": is a directory" : ": not a regular file"));
    }
  }
}

}  // namespace
}  // namespace hapcine
