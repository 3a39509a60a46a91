#include "extract/shot_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "extract/test_frames.h"

namespace hapcine {
namespace {

using testing::MakeFrame;
using testing::NoiseTexture;

// The same picture, its colours pushed towards red by `step` per frame: a
// steady histogram change, like a pan across a changing set.
Frame Tinted(const cv::Mat& texture, double shift, int index) {
  cv::Mat img;
  texture.convertTo(img, -1, 1.0, 0);
  img += cv::Scalar(0, 0, shift);
  return MakeFrame(img, index, 0.5);
}

// A spike is measured against the shot's last few distances, not only its
// calm ones: a steady change (every frame moving the histogram by the same
// amount) is no spike after its start, a jump of 5x that step is one.
TEST(ShotDetectorTest, SpikeIsRelativeToTheRecentDistances) {
  const cv::Mat texture = NoiseTexture({320, 240}, 31);
  ShotDetector detector;
  std::vector<ShotDecision> d;
  double shift = 0;
  for (int i = 0; i < 30; ++i) {
    if (i >= 10) shift += i == 25 ? 20 : 4;  // steady from 10, a jump at 25
    d.push_back(detector.Update(Tinted(texture, shift, i)));
  }
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(d[i].spike) << i;  // still
  // The start of the change is a spike against the still frames before it;
  // a few frames later the change is the new normal.
  EXPECT_TRUE(d[10].spike);
  for (int i = 14; i < 25; ++i) EXPECT_FALSE(d[i].spike) << i << " d=" << d[i].distance;
  EXPECT_TRUE(d[25].spike) << "d=" << d[25].distance << " before " << d[24].distance;
  EXPECT_FALSE(d[26].spike);
  for (const auto& x : d) EXPECT_EQ(x.boundary, ShotBoundary::kNone);
}

// MarkCut() starts the statistics over: the frame after it has no history,
// so it cannot be a spike.
TEST(ShotDetectorTest, MarkCutStartsTheStatisticsOver) {
  const cv::Mat texture = NoiseTexture({320, 240}, 32);
  ShotDetector detector;
  for (int i = 0; i < 10; ++i) detector.Update(Tinted(texture, 0, i));
  EXPECT_TRUE(detector.Update(Tinted(texture, 20, 10)).spike);
  detector.MarkCut();
  EXPECT_FALSE(detector.Update(Tinted(texture, 60, 11)).spike);
}

// Continuity: a picture moved by a fast handheld step and smeared by motion
// blur continues the last one; a cut to an unrelated picture of the same
// colours (look-alike histograms) does not.
TEST(ShotDetectorTest, ContinuityTellsAMovedBlurredPictureFromAnotherOne) {
  const cv::Mat scene = NoiseTexture({900, 600}, 41);
  const cv::Mat other = NoiseTexture({900, 600}, 42);
  const cv::Size decoded(640, 360);
  ShotDetector detector;
  detector.Update(MakeFrame(testing::Shifted(scene, 0, 0, decoded), 0, 0.5));
  cv::Mat moved = testing::Shifted(scene, -60, 25, decoded);  // ~10 % of the width
  cv::blur(moved, moved, cv::Size(31, 1));                     // motion blur
  const ShotDecision step = detector.Update(MakeFrame(moved, 1, 0.5));
  EXPECT_GE(step.continuity, kContinuousPicture);
  const ShotDecision cut = detector.Update(MakeFrame(testing::Shifted(other, 0, 0, decoded), 2, 0.5));
  EXPECT_LT(cut.continuity, kContinuousPicture);
  EXPECT_LT(cut.distance, 0.5) << "look-alike colours: the histograms alone cannot tell";
}

// The picture before a run, moved by the run's motion: the same picture
// moved shows no change, another picture changes every cell, a region
// replaced in one corner changes only the cells it covers.
TEST(ShotDetectorTest, MovedPictureChangeIsTheShareOfThePictureReplaced) {
  const cv::Mat scene = NoiseTexture({900, 600}, 43);
  const cv::Mat other = NoiseTexture({900, 600}, 44);
  const cv::Size decoded(640, 360);
  auto layout = [&](const cv::Mat& img) {
    ShotDetector d;
    d.Update(MakeFrame(img, 0, 0.5));
    return d.layout().clone();
  };
  const cv::Size working(320, 180);
  const cv::Mat before = layout(testing::Shifted(scene, 0, 0, decoded));
  // 80 decoded px right = 40 working px.
  const cv::Matx33d moved_right(1, 0, 40, 0, 1, 0, 0, 0, 1);
  const cv::Mat after = layout(testing::Shifted(scene, 80, 0, decoded));
  EXPECT_LT(MovedPictureChange(before, after, moved_right, working), 0.1);
  // Without the motion the cells do not match.
  EXPECT_GT(MovedPictureChange(before, after, cv::Matx33d::eye(), working), 0.5);
  const cv::Mat replaced = layout(testing::Shifted(other, 80, 0, decoded));
  EXPECT_GE(MovedPictureChange(before, replaced, moved_right, working), 0.9);
  // A mover over a third of the picture's width.
  cv::Mat partly = testing::Shifted(scene, 80, 0, decoded);
  const cv::Rect mover(160, 0, 213, 360);
  testing::Shifted(other, 0, 0, decoded)(mover).copyTo(partly(mover));
  const double share = MovedPictureChange(before, layout(partly), moved_right, working);
  EXPECT_GT(share, 0.15);
  EXPECT_LT(share, 0.6);
  // Moved out of view: nothing to compare.
  const cv::Matx33d far_away(1, 0, 300, 0, 1, 0, 0, 0, 1);
  EXPECT_TRUE(std::isnan(MovedPictureChange(before, after, far_away, working)));
}

}  // namespace
}  // namespace hapcine
