#include "datasets/preview_platform.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "datasets/preview.h"
#include "extract/frame_source.h"

namespace hapcine {
namespace {

PlatformTrack Constant(const PlatformPose& pose) {
  PlatformTrack t;
  for (int i = 0; i < 3; ++i) {
    PlatformSample s;
    s.time_s = i;
    s.pose = i == 0 ? PlatformPose::Zero() : pose;
    t.samples.push_back(s);
  }
  return t;
}

// Topmost row of the moving seat's colour in the first (behind) view.
void MovingSeat(const cv::Mat& img, int* top_row) {
  cv::Mat mask;
  cv::inRange(img, cv::Scalar(30, 200, 240), cv::Scalar(50, 240, 255), mask);
  const cv::Mat behind = mask(cv::Rect(0, 0, img.cols / 3, img.rows));
  *top_row = -1;
  for (int y = 0; y < behind.rows && *top_row < 0; ++y) {
    if (cv::countNonZero(behind.row(y)) > 0) *top_row = y;
  }
}

TEST(PreviewPlatform, TheDrawnSeatRisesWithHeave) {
  PlatformPose up = PlatformPose::Zero();
  up[1] = 0.1;  // 10 cm of heave
  const PlatformTrack track = Constant(up);
  cv::Mat home(300, 900, CV_8UC3, cv::Scalar(0, 0, 0)), raised = home.clone();
  DrawPlatformInset(home, cv::Rect(0, 0, 900, 300), track, 0.0);
  DrawPlatformInset(raised, cv::Rect(0, 0, 900, 300), track, 2.0);
  int top_home = 0, top_raised = 0;
  MovingSeat(home, &top_home);
  MovingSeat(raised, &top_raised);
  ASSERT_GE(top_home, 0);
  // The view is 240 px tall (300 less the text): 1.6 m across 240 px.
  EXPECT_NEAR(top_home - top_raised, 0.1 * 240 / 1.6, 2.0);
}

TEST(PreviewPlatform, PoseIsInterpolatedAndClampedToTheEnds) {
  PlatformPose p = PlatformPose::Zero();
  p[5] = 0.2;
  const PlatformTrack track = Constant(p);
  EXPECT_NEAR(PlatformPoseAt(track, 0.5)[5], 0.1, 1e-12);
  EXPECT_NEAR(PlatformPoseAt(track, -3)[5], 0.0, 1e-12);
  EXPECT_NEAR(PlatformPoseAt(track, 9)[5], 0.2, 1e-12);
  EXPECT_EQ(PlatformPoseAt(PlatformTrack(), 1.0), PlatformPose::Zero());
}

// `preview --platform`: no haptic track needed; the seat is drawn bottom-right.
TEST(PreviewPlatform, RendersAPreviewWithAPlatformTrackOnly) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg CLI not installed";
  namespace fs = std::filesystem;
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_platform_test_tmp";
  fs::create_directories(d);
  const fs::path video = d / "clip.mp4";
  const std::string cmd =
      "ffmpeg -loglevel error -y -f lavfi -i color=c=black:duration=1:size=320x240:rate=20 "
      "-pix_fmt yuv420p " + video.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  PlatformPose p = PlatformPose::Zero();
  p[3] = 0.1;
  PlatformTrack track = Constant(p);
  track.source = "clip.camera.csv";
  {
    std::ofstream out(d / "clip.platform.csv");
    WritePlatformTrack(track, out);
  }
  fs::remove(d / "clip.haptic.csv");
  PreviewOptions o;
  o.video = video.string();
  o.platform_track = (d / "clip.platform.csv").string();
  o.simulate_platform = true;
  o.output = (d / "out.mp4").string();
  EXPECT_EQ(RenderPreview(o), 20);
  FrameSourceOptions fo;
  fo.max_working_side = 0;
  auto src = OpenFrameSource(o.output, fo);
  Frame f;
  ASSERT_TRUE(src->Next(&f));
  const cv::Rect inset(f.bgr.cols / 2, f.bgr.rows / 2, f.bgr.cols / 2, f.bgr.rows / 2);
  EXPECT_GT(cv::mean(f.bgr(inset))[2], cv::mean(f.bgr(cv::Rect(0, 0, 40, 40)))[2] + 5);
  fs::remove_all(d);
}

}  // namespace
}  // namespace hapcine
