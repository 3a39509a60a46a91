#include "datasets/colmap_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

struct Dir {
  fs::path path;
  Dir() {
    path = fs::temp_directory_path() / ("hapcine_colmap_test_" + std::to_string(::getpid()));
    fs::create_directories(path);
  }
  ~Dir() { fs::remove_all(path); }
  void Write(const std::string& name, const std::string& text) { std::ofstream(path / name) << text; }
};

// Two frames: the second is panned 10 degrees left (about world +Y, OpenGL)
// and moved 0.5 m right; one 3-D point 4 m in front of the first camera.
void WriteModel(Dir& d) {
  d.Write("cameras.txt", "# comment\n1 SIMPLE_PINHOLE 480 270 400 240 135\n2 SIMPLE_PINHOLE 480 270 420 240 135\n");
  // cam_from_world (OpenCV). Camera 2's world_from_cam_cv = R_y_cv(-10 deg), centre (0.5, 0, 0).
  const Eigen::Matrix3d F = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Matrix3d R_gl = Eigen::AngleAxisd(DegToRad(10), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d R_wc_cv = F * R_gl * F;
  const Eigen::Matrix3d R_cw = R_wc_cv.transpose();
  const Eigen::Vector3d C(0.5, 0, 0);
  const Eigen::Vector3d t = -R_cw * C;
  const Eigen::Quaterniond q(R_cw);
  std::ostringstream s;
  s.precision(17);
  s << "# images\n1 1 0 0 0 0 0 0 1 frame_000000.jpg\n100 200 7\n";
  s << "2 " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " " << t.x() << " " << t.y() << " "
    << t.z() << " 2 frame_000002.jpg\n\n";
  d.Write("images.txt", s.str());
  d.Write("points3D.txt", "7 0 0 4 255 255 255 0.1 1 0\n");
}

TEST(ColmapModel, ConvertsAxesOriginScaleAndFocal) {
  Dir d;
  WriteModel(d);
  ColmapReadOptions o;
  o.frame_times = {0.0, 0.04, 0.08};
  o.decoded_width = 1920;
  const CameraPath p = ReadColmapTextModel(d.path.string(), o);
  ASSERT_EQ(p.frames.size(), 3u);
  EXPECT_LT(AngleBetweenDeg(p.frames[0].world_from_cam, Eigen::Quaterniond::Identity()), 1e-9);
  EXPECT_EQ(*p.frames[1].confidence, 0);  // not registered: lost
  EXPECT_EQ(p.frames[1].model.value_or(""), kLostModel);
  const CameraFrame& f = p.frames[2];
  const PanTiltRoll ptr = PanTiltRollFromQuaternion(f.world_from_cam);
  EXPECT_NEAR(ptr.pan_deg, 10, 1e-6);
  EXPECT_NEAR(f.center.x(), 0.5 / 4, 1e-9);  // median depth 4 -> unit
  EXPECT_NEAR(f.center.z(), 0, 1e-9);
  EXPECT_NEAR(*f.focal_px, 420 * 4, 1e-9);
  EXPECT_NEAR(p.frames[2].time_s, 0.08, 1e-12);
}

TEST(ColmapModel, MalformedFilesNameFileAndLine) {
  Dir d;
  WriteModel(d);
  d.Write("images.txt", "1 1 0 0 nonsense\n");
  try {
    ReadColmapTextModel(d.path.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("images.txt:1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadColmapTextModel((d.path / "missing").string()), Error);
}

// A model file that is not a regular file is refused with one line (a FIFO
// would block the reader; a directory used to read as empty).
TEST(ColmapModel, ModelFileThatIsNotARegularFileIsRefused) {
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt"}) {
    Dir d;
    WriteModel(d);
    const fs::path bad = d.path / name;
    fs::remove(bad);
    fs::create_directory(bad);
    try {
      ReadColmapTextModel(d.path.string());
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad.string() + ": is a directory");
    }
  }
}

}  // namespace
}  // namespace hapcine
