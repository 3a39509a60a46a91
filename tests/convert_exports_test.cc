// End-to-end: `hapcine convert` exports of a multi-shot film (one file per
// shot, --shot N) and their one-line errors.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;
using hapcine_test::Slurp;

namespace {

class ConvertExportsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() /
            ("hapcine_convert_exports_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override { fs::remove_all(work_); }

  // Shots 0, 1, 2 of 2, 1 and 3 frames, each starting at the origin.
  fs::path ThreeShots(bool with_size = true, const std::string& extra_header = "") const {
    const fs::path p = work_ / "film.camera.csv";
    std::ofstream out(p);
    if (with_size) out << "# width=1280\n# height=720\n";
    out << extra_header;
    out << "# fps=24\nframe,time_s,x,y,z,qw,qx,qy,qz,fov_deg,shot\n";
    const int shot_of[] = {0, 0, 1, 2, 2, 2};
    for (int i = 0; i < 6; ++i) {
      out << i << "," << i / 24.0 << ",0,0," << -0.1 * i << ",1,0,0,0,60," << shot_of[i] << "\n";
    }
    return p;
  }
  static int Lines(const fs::path& p) {
    const std::string text = Slurp(p);
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  }
  static bool OneLine(const std::string& err) {
    return !err.empty() && err.find('\n') == err.size() - 1;
  }

  fs::path work_;
};

TEST_F(ConvertExportsTest, TumAndKittiWriteOneFilePerShot) {
  const fs::path in = ThreeShots();
  for (const std::string option : {"--to-tum", "--to-kitti", "--to-nuke-chan"}) {
    const RunResult r = RunHapcine("convert " + Quote(in) + " " + option + " " +
                                       Quote(work_ / "out.txt"), work_);
    ASSERT_EQ(r.exit_code, 0) << option << "\n" << r.err;
    EXPECT_FALSE(fs::exists(work_ / "out.txt")) << option;
    const int header = option == std::string("--to-tum") ? 1 : 0;
    EXPECT_EQ(Lines(work_ / "out.shot000.txt"), header + 2) << option;
    EXPECT_EQ(Lines(work_ / "out.shot001.txt"), header + 1) << option;  // a one-frame shot
    EXPECT_EQ(Lines(work_ / "out.shot002.txt"), header + 3) << option;
    fs::remove(work_ / "out.shot000.txt");
    fs::remove(work_ / "out.shot001.txt");
    fs::remove(work_ / "out.shot002.txt");
  }
  // Each shot's TUM file reads back on its own.
  ASSERT_EQ(RunHapcine("convert " + Quote(in) + " --to-tum " + Quote(work_ / "t.txt"), work_)
                .exit_code, 0);
  const RunResult back = RunHapcine("convert --from-tum " + Quote(work_ / "t.shot002.txt") +
                                        " --fov 60 -o " + Quote(work_ / "back.camera.csv"), work_);
  EXPECT_EQ(back.exit_code, 0) << back.err;
}

TEST_F(ConvertExportsTest, ShotOptionWritesOneShotAsNamed) {
  const fs::path in = ThreeShots();
  RunResult r = RunHapcine("convert " + Quote(in) + " --to-kitti " + Quote(work_ / "k.txt") +
                               " --shot 2", work_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Lines(work_ / "k.txt"), 3);
  // The shot starts at the identity; it travels forward (+z in KITTI).
  std::istringstream rows(Slurp(work_ / "k.txt"));
  std::string first, second;
  std::getline(rows, first);
  std::getline(rows, second);
  EXPECT_EQ(first, "1 0 0 0 0 1 0 0 0 0 1 0");
  std::istringstream numbers(second);
  double v[12] = {};
  for (double& x : v) numbers >> x;
  EXPECT_NEAR(v[11], 0.1, 1e-12) << second;
  EXPECT_NEAR(v[3], 0, 1e-12) << second;
  r = RunHapcine("convert " + Quote(in) + " --to-tum " + Quote(work_ / "t.txt") + " --shot 5",
                 work_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine convert: " + in.string() + ": no frame of shot 5 (shots 0 to 2)\n");
  EXPECT_FALSE(fs::exists(work_ / "t.txt"));
}

TEST_F(ConvertExportsTest, BadInputsAreOneLine) {
  const fs::path empty = work_ / "empty.camera.csv";
  std::ofstream(empty) << "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n";
  for (const std::string option : {"--to-tum", "--to-kitti", "--to-nuke-chan", "--to-blender"}) {
    const RunResult r = RunHapcine("convert " + Quote(empty) + " " + option + " " +
                                       Quote(work_ / "o"), work_);
    EXPECT_EQ(r.exit_code, 1) << option;
    EXPECT_TRUE(OneLine(r.err)) << r.err;
    EXPECT_FALSE(fs::exists(work_ / "o")) << option;
  }
  // A .chan needs the aspect ratio for its vertical field of view.
  const RunResult r = RunHapcine("convert " + Quote(ThreeShots(false)) + " --to-nuke-chan " +
                                     Quote(work_ / "c.chan"), work_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(OneLine(r.err)) << r.err;
  EXPECT_NE(r.err.find("width/height"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "c.shot000.chan"));
  // Two exports at once is a usage error.
  EXPECT_EQ(RunHapcine("convert " + Quote(ThreeShots()) + " --to-tum " + Quote(work_ / "a") +
                           " --to-kitti " + Quote(work_ / "b"), work_)
                .exit_code, 2);
}

TEST_F(ConvertExportsTest, BlenderScriptHoldsEveryShot) {
  const RunResult r = RunHapcine("convert " + Quote(ThreeShots()) + " --to-blender " +
                                     Quote(work_ / "film.py") + " --sensor-width-mm 24.89", work_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = Slurp(work_ / "film.py");
  EXPECT_NE(script.find("SENSOR_WIDTH_MM = 24.89\n"), std::string::npos);
  EXPECT_NE(script.find("FPS = 24\n"), std::string::npos);
  for (const char* shot : {"(0, '''\n1 ", "(1, '''\n3 ", "(2, '''\n4 "}) {
    EXPECT_NE(script.find(shot), std::string::npos) << shot;
  }
}

TEST_F(ConvertExportsTest, BlenderSensorWidthFromTheHeader) {
  RunResult r = RunHapcine("convert " + Quote(ThreeShots(true, "# sensor_width_mm=23.5\n")) +
                               " --to-blender " + Quote(work_ / "a.py"), work_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(Slurp(work_ / "a.py").find("SENSOR_WIDTH_MM = 23.5\n"), std::string::npos);
  // The option wins over the header.
  r = RunHapcine("convert " + Quote(work_ / "film.camera.csv") + " --to-blender " +
                     Quote(work_ / "b.py") + " --sensor-width-mm 36", work_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(Slurp(work_ / "b.py").find("SENSOR_WIDTH_MM = 36\n"), std::string::npos);
  r = RunHapcine("convert " + Quote(ThreeShots(true, "# sensor_width_mm=wide\n")) +
                     " --to-blender " + Quote(work_ / "c.py"), work_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(OneLine(r.err)) << r.err;
  EXPECT_NE(r.err.find("sensor_width_mm='wide'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "c.py"));
}

}  // namespace
