// End-to-end: a VFX-style plate (plate.%04d.png numbered from 1001) through
// `hapcine estimate --fps 25`: the rate in the header and the times, each
// image's number in the `source_frame` column; the same through `hapcine
// make`, which reuses its camera path; --fps on a video is refused.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/camera_path.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

namespace {

TEST(ImageSequenceTest, PlateFrom1001KeepsItsNumbersAndRate) {
  const fs::path dir = fs::temp_directory_path() / ("hapcine_plate_" + std::to_string(getpid()));
  fs::create_directories(dir / "plate");
  // FFmpeg's test pattern, 8 stills: plate.1001.png ... plate.1008.png.
  const std::string cmd = "ffmpeg -nostdin -loglevel error -f lavfi -i testsrc=size=192x108:rate=24 "
                          "-frames:v 8 -start_number 1001 " + Quote(dir / "plate" / "plate.%04d.png") +
                          " -frames:v 8 -pix_fmt yuv420p " + Quote(dir / "clip.mp4");
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  const fs::path out = dir / "plate.camera.csv";
  RunResult r = RunHapcine("estimate " + Quote(dir / "plate" / "plate.%04d.png") + " --fps 25 -q -o " + Quote(out), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const hapcine::CameraPath path = hapcine::ReadCameraPathFile(out.string());
  EXPECT_DOUBLE_EQ(path.fps(), 25);
  ASSERT_EQ(path.frames.size(), 8u);
  ASSERT_EQ(path.source_frames.size(), 8u);
  for (size_t i = 0; i < path.frames.size(); ++i) {
    EXPECT_EQ(path.frames[i].frame, static_cast<int>(i));
    EXPECT_NEAR(path.frames[i].time_s, i / 25.0, 1e-6);
    EXPECT_EQ(path.source_frames[i], static_cast<int>(1001 + i));
  }

  // make: the same plate is a film; outputs beside the images' folder (not
  // among the images), named after the text before the number.
  const std::string pattern = Quote(dir / "plate" / "plate.%04d.png");
  r = RunHapcine("make " + pattern + " --fps 25 -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "plate.camera.csv"));
  EXPECT_TRUE(fs::is_regular_file(dir / "plate.haptic.csv"));
  EXPECT_EQ(hapcine::ReadCameraPathFile((dir / "plate.camera.csv").string()).source_frames.at(7), 1008);
  r = RunHapcine("make " + pattern + " --fps 25 -q --model semantic", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("estimate            reused"), std::string::npos) << r.err;
  r = RunHapcine("make " + pattern + " --preview", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--preview needs a video file"), std::string::npos) << r.err;

  r = RunHapcine("estimate " + Quote(dir / "clip.mp4") + " --fps 25 -o " + Quote(dir / "v.camera.csv"), dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--fps is for image folders and patterns"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "v.camera.csv"));
  fs::remove_all(dir);
}

}  // namespace
