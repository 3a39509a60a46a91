// `hapcine haptics --seat platform.json`, `plot platform`: the motion-platform
// branch of the CLI, end to end on a written camera path.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/haptic_track.h"
#include "platform/platform_track.h"
#include "testpaths/test_paths.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

namespace {

class PlatformCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hapcine_platform_cli_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    // A traveling to the right: 1 s still, 2 m in 3 s, 1 s still, 24 fps.
    std::ofstream out(dir_ / "travel.camera.csv");
    out << "# fps=24\nframe,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n";
    for (int i = 0; i <= 120; ++i) {
      const double t = i / 24.0, u = std::clamp((t - 1) / 3, 0.0, 1.0);
      out << i << ',' << t << ',' << 1 - std::cos(3.141592653589793 * u) << ",0,0,1,0,0,0,50\n";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Seat(const char* name) const {
    return Quote(fs::path(HAPCINE_SOURCE_DIR) / "haptics" / name);
  }
  fs::path dir_;
};

TEST_F(PlatformCliTest, APlatformSeatFileWritesAPlatformTrack) {
  const fs::path out = dir_ / "travel.platform.csv";
  RunResult r = RunHapcine("haptics " + Quote(dir_ / "travel.camera.csv") + " --seat " +
                               Seat("platform_stewart.json") + " -o " + Quote(out), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const hapcine::PlatformTrack t = hapcine::ReadPlatformTrackFile(out.string());
  EXPECT_EQ(t.dofs, "sway heave surge pitch yaw roll");
  ASSERT_FALSE(t.samples.empty());
  ASSERT_TRUE(t.samples.back().legs.has_value());
  double sway = 0;
  for (const auto& s : t.samples) sway = std::max(sway, s.pose[0]);
  EXPECT_GT(sway, 0.05);  // traveling right: sway right
  r = RunHapcine("plot platform " + Quote(out) + " -o " + Quote(dir_ / "fig") + " --format png", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "fig.png"));
}

TEST_F(PlatformCliTest, HapSeatFilesStillMakeHapticTracks) {
  const fs::path out = dir_ / "travel.haptic.csv";
  const RunResult r = RunHapcine("haptics " + Quote(dir_ / "travel.camera.csv") + " --seat " +
                                     Seat("hapseat.json") + " -o " + Quote(out), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(hapcine::ReadHapticTrackFile(out.string()).model, "cinematic");
}

TEST_F(PlatformCliTest, MisuseAndBadFilesAreRefusedWithNoOutput) {
  const std::string cam = Quote(dir_ / "travel.camera.csv");
  const fs::path out = dir_ / "x.platform.csv";
  RunResult r = RunHapcine("haptics " + cam + " --seat " + Seat("platform_3dof.json") + " -o " +
                               Quote(out) + " --hjif " + Quote(dir_ / "x.hjif"), dir_);
  EXPECT_EQ(r.exit_code, 2);
  r = RunHapcine("haptics " + cam + " --seat " + Seat("platform_3dof.json") + " --model semantic -o " +
                     Quote(out), dir_);
  EXPECT_EQ(r.exit_code, 2);
  std::ofstream(dir_ / "bad.json") << "{\"type\": \"platform\", \"dofs\": {\"heave\": {}}}";
  r = RunHapcine("haptics " + cam + " --seat " + Quote(dir_ / "bad.json") + " -o " + Quote(out), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = RunHapcine("haptics --seat " + Seat("platform_3dof.json") + " --print-seat", dir_);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("\"type\": \"platform\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"tilt_rate_deg_s\""), std::string::npos) << r.out;
}

}  // namespace
