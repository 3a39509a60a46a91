// End-to-end: a continuous take stays one shot. The test-split crane
// (grain, vignetting, motion blur, other textures) changes its histogram
// slowly for most of its move, which the shot detector reads as a candidate
// dissolve; the tracks' chained motion must then be checked over the whole
// run, since the crane's parallax passes every single frame's homography
// test yet drifts by several pixels of the picture comparison over 80 frames.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <string>

#include "core/camera_path.h"
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
