#include "extract/affine_lk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "extract/test_frames.h"

namespace hapcine {
namespace {

cv::Mat GrayNoise(int seed) {
  cv::Mat gray;
  cv::cvtColor(testing::NoiseTexture({320, 240}, seed), gray, cv::COLOR_BGR2GRAY);
  return gray;
}

// The picture turned by `deg` and scaled by `scale` about `centre`, then
// moved by `shift`; `linear` receives the image offset per anchor offset.
cv::Mat Turned(const cv::Mat& gray, double deg, double scale, cv::Point2f centre, cv::Point2f shift,
               cv::Matx22f* linear) {
  cv::Mat m = cv::getRotationMatrix2D(centre, deg, scale);
  m.at<double>(0, 2) += shift.x;
  m.at<double>(1, 2) += shift.y;
  *linear = cv::Matx22f(float(m.at<double>(0, 0)), float(m.at<double>(0, 1)), float(m.at<double>(1, 0)),
                        float(m.at<double>(1, 1)));
  cv::Mat out;
  cv::warpAffine(gray, out, m, gray.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return out;
}

// A patch turned by 20 degrees and shrunk by 15 % (a view that turned):
// found from a start 0.7 px off with no shape change, to a few hundredths
// of a pixel, with its shape, gain and bias (brighter, less contrast).
TEST(AffineLkTest, AlignsAPatchThatTurnedAndShrank) {
  const cv::Mat anchor_image = GrayNoise(3);
  const cv::Point2f centre(160, 120), shift(2.3f, -1.6f);
  cv::Matx22f linear;
  cv::Mat image = Turned(anchor_image, 20, 0.85, centre, shift, &linear);
  image.convertTo(image, CV_8U, 0.8, 30);
  for (const cv::Point2f anchor : {cv::Point2f(150.3f, 110.6f), cv::Point2f(175.0f, 131.2f)}) {
    const cv::Point2f truth = centre + shift + cv::Point2f(linear(0, 0) * (anchor.x - centre.x) + linear(0, 1) * (anchor.y - centre.y),
                                                           linear(1, 0) * (anchor.x - centre.x) + linear(1, 1) * (anchor.y - centre.y));
    AffinePatchFit start;
    start.position = truth + cv::Point2f(0.5f, -0.5f);
    const AffinePatchFit fit = AlignAffinePatch(anchor_image, anchor, image, start, 8);
    ASSERT_TRUE(fit.ok);
    EXPECT_LT(cv::norm(fit.position - truth), 0.05) << anchor;
    EXPECT_LT(cv::norm(fit.linear - linear), 0.03) << anchor;
    EXPECT_LT(fit.residual, 0.1) << anchor;
  }
}

// The residual tells a patch that drifted onto another point: the same
// search on an unrelated picture converges, if at all, to a residual many
// times that of the true match.
TEST(AffineLkTest, AnotherPictureLeavesALargeResidual) {
  const cv::Mat anchor_image = GrayNoise(3), other = GrayNoise(4);
  AffinePatchFit start;
  start.position = {160, 120};
  const AffinePatchFit same = AlignAffinePatch(anchor_image, {160, 120}, anchor_image, start, 8);
  const AffinePatchFit wrong = AlignAffinePatch(anchor_image, {160, 120}, other, start, 8);
  ASSERT_TRUE(same.ok);
  EXPECT_LT(same.residual, 0.01);
  if (wrong.ok) {
    EXPECT_GT(wrong.residual, 0.3);
  }
}

// Degenerate cases: a flat patch (nothing to align: fails inside), a patch
// whose window leaves the anchor image, a start outside the image (nothing
// measured: not inside).
TEST(AffineLkTest, FlatOrOutsidePatchesDoNotAlign) {
  const cv::Mat flat(240, 320, CV_8UC1, cv::Scalar(128)), noise = GrayNoise(5);
  AffinePatchFit start;
  start.position = {160, 120};
  const AffinePatchFit flat_fit = AlignAffinePatch(flat, {160, 120}, flat, start, 8);
  EXPECT_FALSE(flat_fit.ok);
  EXPECT_TRUE(flat_fit.inside);
  const AffinePatchFit border_anchor = AlignAffinePatch(noise, {3, 120}, noise, start, 8);
  EXPECT_FALSE(border_anchor.ok);
  EXPECT_FALSE(border_anchor.inside);
  start.position = {-20, 120};
  const AffinePatchFit outside = AlignAffinePatch(noise, {160, 120}, noise, start, 8);
  EXPECT_FALSE(outside.ok);
  EXPECT_FALSE(outside.inside);
}

}  // namespace
}  // namespace hapcine
