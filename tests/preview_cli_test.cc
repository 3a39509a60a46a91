// End-to-end: `hapcine preview` with a range. A good range writes the
// preview with the film's sound; a bad one (empty, reversed, past the end,
// not a time) is a usage error: exit 2, one line naming the option, nothing
// written.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

namespace {

TEST(PreviewCli, BadRangeIsAUsageErrorAndWritesNothing) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::temp_directory_path() / ("hapcine_preview_cli_" + std::to_string(getpid()));
  fs::create_directories(d);
  const std::string clip = (d / "clip.mp4").string();
  const std::string make_clip =
      "ffmpeg -loglevel error -y -f lavfi -i color=c=gray:duration=2:size=160x120:rate=20 "
      "-f lavfi -i sine=frequency=440:duration=2 -c:a aac -pix_fmt yuv420p -shortest " + clip;
  ASSERT_EQ(std::system(make_clip.c_str()), 0);
  {
    std::ofstream t(d / "clip.haptic.csv");
    t << "# rate_hz=10\n# model=none\n# source=clip.mp4\n"
         "time_s,head_x,head_y,head_z,left_x,left_y,left_z,right_x,right_y,right_z\n"
         "0,0,0,0,0,0,0,0,0,0\n2,0,0,0,0,0,0,0,0,0\n";
  }
  const std::string out = (d / "out.mp4").string();
  const RunResult good = RunHapcine("preview " + Quote(clip) + " --from 0.5 --to 00:00:01:10 -o " + Quote(out), d);
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.err.find("wrote " + out + " (20 frames)"), std::string::npos) << good.err;
  fs::remove(out);
  for (const std::string range : {"--from 1.5 --to 0.5", "--from 3", "--from abc", "--to 00:00:00:20"}) {
    const RunResult r = RunHapcine("preview " + Quote(clip) + " " + range + " -o " + Quote(out), d);
    EXPECT_EQ(r.exit_code, 2) << range << ": " << r.err;
    EXPECT_EQ(r.err.rfind("hapcine preview: --", 0), 0u) << range << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << range << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << range;
  }
  fs::remove_all(d);
}

}  // namespace
