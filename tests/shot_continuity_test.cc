// End-to-end: a continuous take stays one shot. The test-split crane
// (grain, vignetting, motion blur, other textures) changes its histogram
// slowly for most of its move, which the shot detector reads as a candidate
// dissolve; the tracks' chained motion must then be checked over the whole
// run, since the crane's parallax passes every single frame's homography
// test yet drifts by several pixels of the picture comparison over 80 frames.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "core/camera_path.h"
#include "core/rotation.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

TEST(ShotContinuityTest, TestSplitCraneIsOneShot) {
  const fs::path dir = fs::temp_directory_path() / ("hapcine_crane_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const RunResult synth = RunHapcine(
      "synth crane_shot --variant test --width 320 --height 180 -o " + Quote(dir), dir);
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const fs::path estimate = dir / "crane.camera.csv";
  const RunResult run = RunHapcine("estimate " + Quote(dir / "crane_shot.mp4") + " -q -o " +
                                       Quote(estimate),
                                   dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const hapcine::CameraPath path = hapcine::ReadCameraPathFile(estimate.string());
  std::set<int> shots;
  for (const hapcine::CameraFrame& f : path.frames) shots.insert(f.shot.value_or(0));
  EXPECT_EQ(shots.size(), 1u) << "a continuous crane was split into shots";
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// A blur burst inside a pan (synth slow_pan, 320x180, frames 80-84 box
// blurred past what KLT and the descriptors can follow; 8:4 also moves the
// histogram past the hard cut's threshold): the frames of the burst are
// lost, but the first sharp frame is linked back to the last one before the
// burst by descriptors, so the take stays one shot with a continuous pose:
// the rotation after the burst is within the presets' target (0.1 deg) of
// the truth's, both taken relative to frame 0.
TEST(ShotContinuityTest, BlurBurstInAPanIsLostButKeepsTheShot) {
  const fs::path dir =
      fs::temp_directory_path() / ("hapcine_blur_burst_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const RunResult synth =
      RunHapcine("synth slow_pan --seed 2 --width 320 --height 180 -o " + Quote(dir), dir);
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const hapcine::CameraPath truth =
      hapcine::ReadCameraPathFile((dir / "slow_pan.camera.csv").string());
  for (const std::string blur : {"6:2", "8:4"}) {
    SCOPED_TRACE("boxblur " + blur);
    const fs::path blurred = dir / "blurred.mp4";
    const std::string cmd = "ffmpeg -nostdin -loglevel error -y -i " + Quote(dir / "slow_pan.mp4") +
                            " -vf \"boxblur=" + blur +
                            ":enable='between(n,80,84)'\" -c:v libx264 -crf 18"
                            " -pix_fmt yuv420p " +
                            Quote(blurred);
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const fs::path estimate = dir / "blurred.camera.csv";
    const RunResult run =
        RunHapcine("estimate " + Quote(blurred) + " -q -o " + Quote(estimate), dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const hapcine::CameraPath path = hapcine::ReadCameraPathFile(estimate.string());
    ASSERT_EQ(path.frames.size(), truth.frames.size());
    ASSERT_GT(path.frames.size(), 120u);
    const Eigen::Quaterniond est0(path.frames[0].world_from_cam),
        true0(truth.frames[0].world_from_cam);
    for (size_t i = 0; i < path.frames.size(); ++i) {
      const hapcine::CameraFrame& f = path.frames[i];
      EXPECT_EQ(f.shot.value_or(0), 0) << i;
      EXPECT_EQ(hapcine::IsLost(f), i >= 80 && i <= 84) << i;
      if (i < 85) continue;
      const Eigen::Quaterniond est(f.world_from_cam), truth_i(truth.frames[i].world_from_cam);
      const double error =
          hapcine::AngleBetweenDeg(est0.conjugate() * est, true0.conjugate() * truth_i);
      EXPECT_LT(error, 0.1) << i;
    }
  }
  // --no-bridge-breaks: the break splits the shot, as before the bridge.
  const fs::path split = dir / "split.camera.csv";
  const RunResult run = RunHapcine(
      "estimate " + Quote(dir / "blurred.mp4") + " -q --no-bridge-breaks -o " + Quote(split), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_GT(hapcine::ReadCameraPathFile(split.string()).frames.back().shot.value_or(0), 0);
  std::error_code ec;
  fs::remove_all(dir, ec);
}
