#include "datasets/preview_burn_in.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include <opencv2/imgproc.hpp>

namespace hapcine {
namespace {

TEST(PreviewBurnIn, TimecodeCountsFramesAtTheNominalRate) {
  EXPECT_EQ(Timecode(0, 24), "00:00:00:00");
  EXPECT_EQ(Timecode(62.5, 24), "00:01:02:12");
  EXPECT_EQ(Timecode(3600 + 23.0 / 24, 24), "01:00:00:23");
  // 23.976: frame 24 is the second second's first frame, as an editor counts.
  EXPECT_EQ(Timecode(24 * 1001.0 / 24000, 24000.0 / 1001), "00:00:01:00");
  EXPECT_EQ(Timecode(-1, 25), "00:00:00:00");
}

TEST(PreviewBurnIn, TimesAreSecondsOrTimecodes) {
  EXPECT_DOUBLE_EQ(ParsePreviewTime("62.5", 24, "--from"), 62.5);
  EXPECT_DOUBLE_EQ(ParsePreviewTime("0", 24, "--from"), 0);
  EXPECT_DOUBLE_EQ(ParsePreviewTime("00:01:02:12", 24, "--from"), 62.5);
  EXPECT_DOUBLE_EQ(ParsePreviewTime("1:02.5", 24, "--from"), 62.5);
  EXPECT_DOUBLE_EQ(ParsePreviewTime("1:00:02.5", 24, "--from"), 3602.5);
  // The timecode and Timecode() agree at a non-integer rate.
  const double fps = 30000.0 / 1001;
  EXPECT_EQ(Timecode(ParsePreviewTime("00:10:00:17", fps, "--to"), fps), "00:10:00:17");
  for (const char* bad : {"", "-1", "abc", "1e3", "00:00:01:24", "00:60:00:00", "1:2:3:4:5",
                          "00:00:01:", ":5", "nan", "1:60"}) {
    EXPECT_THROW(ParsePreviewTime(bad, 24, "--from"), UsageError) << bad;
  }
  try {
    ParsePreviewTime("00:00:01:30", 25, "--to");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--to: '00:00:01:30'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("FF < 25"), std::string::npos) << e.what();
  }
}

CameraFrame FrameAt(double t, int shot, const char* model) {
  CameraFrame f;
  f.time_s = t;
  f.shot = shot;
  f.model = model;
  return f;
}

TEST(PreviewBurnIn, LabelsComeFromThePathAndTheTrackOrTheClassifier) {
  CameraPath path;
  path.frames = {FrameAt(0, 0, "static"), FrameAt(0.5, 0, "pan"), FrameAt(1.0, 1, "lost")};
  HapticTrack track;
  for (int i = 0; i <= 15; ++i) {
    HapticSample s;
    s.time_s = i / 10.0;
    s.effect = i < 5 ? "none" : "traveling";
    track.samples.push_back(s);
  }
  const BurnInLabels semantic(path, track, {});
  EXPECT_EQ(semantic.At(0.2, 24),
            (std::vector<std::string>{"00:00:00:05", "shot 0  camera static", "effect none"}));
  EXPECT_EQ(semantic.At(0.75, 24), (std::vector<std::string>{"00:00:00:18", "shot 0  camera pan",
                                                             "effect traveling (crab_walk)"}));
  EXPECT_EQ(semantic.At(1.2, 24)[1], "shot 1  camera lost");
  // A track without an effect column: the classifier's segments.
  for (auto& s : track.samples) s.effect.reset();
  EffectSegment crane;
  crane.start_s = 0.4;
  crane.end_s = 0.9;
  crane.effect = CameraEffect::kCraneShot;
  const BurnInLabels classified(path, track, {crane});
  EXPECT_EQ(classified.At(0.5, 24)[2], "effect crane_shot (flying_away)");
  EXPECT_EQ(classified.At(0.95, 24)[2], "effect none");
  // No camera path and no effect column: only the timecode (and the
  // track's shot when it has one).
  const CameraPath none;
  EXPECT_EQ(BurnInLabels(none, track, {}).At(0.5, 24), std::vector<std::string>{"00:00:00:12"});
  track.samples[5].shot = 3;
  EXPECT_EQ(BurnInLabels(none, track, {}).At(0.5, 24),
            (std::vector<std::string>{"00:00:00:12", "shot 3"}));
  // Before the first frame: no shot or camera model to name.
  EXPECT_EQ(BurnInLabels(path, HapticTrack(), {}).At(-1, 24),
            (std::vector<std::string>{"00:00:00:00", "effect none"}));
}

TEST(PreviewBurnIn, TextIsDrawnWithAnOutlineAtSmallSizes) {
  for (const cv::Scalar& grey : {cv::Scalar::all(0), cv::Scalar::all(255)}) {
    cv::Mat img(120, 160, CV_8UC3, grey);
    DrawBurnIn(img, {"00:00:01:05", "shot 2  camera pan"});
    // Both white strokes and dark outline show, on black and on white.
    cv::Mat gray;
    cv::cvtColor(img, gray, cv::COLOR_BGR2GRAY);
    const cv::Mat text_area = gray(cv::Rect(0, 0, 160, 40));
    EXPECT_GT(cv::countNonZero(text_area > 200), 20);
    EXPECT_GT(cv::countNonZero(text_area < 50), 20);
    EXPECT_EQ(cv::countNonZero(gray(cv::Rect(0, 60, 160, 60)) != grey[0]), 0);
  }
}

}  // namespace
}  // namespace hapcine
