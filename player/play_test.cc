#include "player/play.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {
namespace fs = std::filesystem;

fs::path TempDir() {
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "play_test_tmp";
  fs::create_directories(d);
  return d;
}

void WriteTrack(const fs::path& path, double duration_s) {
  HapticTrack t;
  t.rate_hz = 50;
  t.model = "cinematic";
  t.source = "test";
  for (int i = 0; i <= static_cast<int>(duration_s * 50); ++i) {
    HapticSample s;
    s.time_s = i / 50.0;
    s.pos_m[1] = Eigen::Vector3d(0.01, 0, 0);
    t.samples.push_back(s);
  }
  WriteHapticTrackFile(t, path.string());
}

TEST(Play, FindsTheSiblingTrackOrSaysWhereItLooked) {
  const fs::path d = TempDir();
  WriteTrack(d / "clip.haptic.csv", 0.2);
  EXPECT_EQ(ResolveTrackPath((d / "clip.mp4").string(), ""), (d / "clip.haptic.csv").string());
  try {
    ResolveTrackPath((d / "other.mp4").string(), "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other.haptic.csv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ResolveTrackPath("x.mp4", (d / "missing.haptic.csv").string()), Error);
}

TEST(Play, WallClockPlayOnTheSimFinishes) {
  const fs::path d = TempDir();
  WriteTrack(d / "short.haptic.csv", 0.2);
  PlayOptions o;
  o.track = (d / "short.haptic.csv").string();
  o.wall_clock = true;
  o.device = "sim";
  o.print_stats = true;
  o.loop.start_ramp_s = 0.05;
  o.loop.end_ramp_s = 0.05;
  o.max_run_s = 5;
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished);
  EXPECT_GT(r.stats.ticks, 100);
  EXPECT_NE(log.str().find("period p50"), std::string::npos) << log.str();
}

TEST(Play, BadOptionsAndNoDeviceAreClear) {
  PlayOptions o;
  o.device = "joystick";
  o.video = "x.mp4";
  std::ostringstream log;
  EXPECT_THROW(Play(o, log), UsageError);
  o.device = "falcon";
  o.video.clear();
  o.wall_clock = true;
  const fs::path d = TempDir();
  WriteTrack(d / "f.haptic.csv", 0.2);
  o.track = (d / "f.haptic.csv").string();
  try {
    Play(o, log);
    FAIL() << "no Falcon here, yet it played";
  } catch (const Error& e) {
    // This machine has no Falcon: the message says what was found.
    EXPECT_NE(std::string(e.what()).find("0403:cb48"), std::string::npos) << e.what();
  }
}

TEST(Play, HeadlessMpvPlaysAGeneratedClip) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = TempDir();
  const fs::path video = d / "tiny.mp4";
  if (!fs::exists(video)) {
    const std::string cmd =
        "ffmpeg -loglevel error -y -f lavfi -i testsrc=duration=1:size=64x48:rate=25 -pix_fmt "
        "yuv420p " +
        video.string();
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }
  WriteTrack(d / "tiny.haptic.csv", 1.0);
  PlayOptions o;
  o.video = video.string();
  o.headless = true;
  o.device = "sim";
  o.loop.end_ramp_s = 0.1;
  o.max_run_s = 10;
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished) << log.str();
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // mpv's clock reached the end of the 1 s clip.
  EXPECT_GT(r.stats.extrapolation_error.count() + r.stats.ticks, 500);
  // A track 3 s longer than the clip is reported.
  WriteTrack(d / "long.haptic.csv", 4.0);
  o.track = (d / "long.haptic.csv").string();
  o.strict_duration = true;
  EXPECT_THROW(Play(o, log), Error);
}

}  // namespace
}  // namespace hapcine
