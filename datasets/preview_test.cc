#include "datasets/preview.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/haptic_track.h"
#include "extract/frame_source.h"

namespace hapcine {
namespace {
namespace fs = std::filesystem;

TEST(Preview, RendersEveryFrameWithTheInsetAndWritesAtomically) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_test_tmp";
  fs::create_directories(d);
  const fs::path video = d / "clip.mp4";
  const std::string cmd =
      "ffmpeg -loglevel error -y -f lavfi -i color=c=black:duration=1:size=160x120:rate=20 "
      "-pix_fmt yuv420p " +
      video.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  HapticTrack t;
  t.rate_hz = 20;
  t.model = "cinematic";
  t.source = "clip.mp4";
  for (int i = 0; i <= 20; ++i) {
    HapticSample s;
    s.time_s = i / 20.0;
    s.pos_m[0] = Eigen::Vector3d(0.04 * i / 20.0, 0.03, 0);
    t.samples.push_back(s);
  }
  WriteHapticTrackFile(t, (d / "clip.haptic.csv").string());
  PreviewOptions o;
  o.video = video.string();
  o.output = (d / "out.mp4").string();
  fs::remove(o.output);
  EXPECT_EQ(RenderPreview(o), 20);
  ASSERT_TRUE(fs::exists(o.output));
  // The inset is drawn: the black clip is no longer black bottom-right.
  FrameSourceOptions fo;
  fo.max_working_side = 0;
  auto src = OpenFrameSource(o.output, fo);
  Frame f;
  ASSERT_TRUE(src->Next(&f));
  const cv::Rect inset(f.bgr.cols / 2, f.bgr.rows / 2, f.bgr.cols / 2, f.bgr.rows / 2);
  EXPECT_GT(cv::mean(f.bgr(inset))[0] + cv::mean(f.bgr(inset))[1], 5.0);
  EXPECT_LT(cv::mean(f.bgr(cv::Rect(0, 0, 20, 20)))[0], 5.0);
  // With a simulated response, its ring (light blue) is drawn too; the
  // callback gets the track that was read.
  auto count_ring_pixels = [](const cv::Mat& bgr) {
    int n = 0;
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x) {
        const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
        n += p[0] > 180 && p[1] > 130 && p[1] < 230 && p[2] < 110;
      }
    return n;
  };
  o.inset_fraction = 1;  // panels big enough to draw at 160x120
  fs::remove(o.output);
  ASSERT_EQ(RenderPreview(o), 20);
  auto src1 = OpenFrameSource(o.output, fo);
  ASSERT_TRUE(src1->Next(&f));
  EXPECT_EQ(count_ring_pixels(f.bgr), 0);
  size_t rows_seen = 0;
  o.simulate = [&rows_seen](const HapticTrack& targets) {
    rows_seen = targets.samples.size();
    HapticTrack r = targets;
    for (auto& s : r.samples) s.pos_m[2] = Eigen::Vector3d(-0.03, 0.02, 0.03);
    return r;
  };
  fs::remove(o.output);
  EXPECT_EQ(RenderPreview(o), 20);
  EXPECT_EQ(rows_seen, t.samples.size());
  auto src2 = OpenFrameSource(o.output, fo);
  ASSERT_TRUE(src2->Next(&f));
  EXPECT_GT(count_ring_pixels(f.bgr), 5);
  o.simulate = nullptr;
  // Bad input: no output left behind.
  o.video = (d / "missing.mp4").string();
  o.track = (d / "clip.haptic.csv").string();
  o.output = (d / "bad.mp4").string();
  EXPECT_THROW(RenderPreview(o), Error);
  EXPECT_FALSE(fs::exists(o.output));
}

}  // namespace
}  // namespace hapcine
