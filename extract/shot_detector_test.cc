#include "extract/shot_detector.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace hapcine
