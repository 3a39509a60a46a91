#include "extract/vignetting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace hapcine {
namespace {

// A smooth random texture (8-bit, mean ~128), panned by `dx` px a frame.
cv::Mat Texture(cv::Size size, int seed) {
  cv::Mat m(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(m, m, cv::Size(0, 0), 6);
  cv::normalize(m, m, 60, 200, cv::NORM_MINMAX);
  return m;
}

// Frame t of a pan over `texture` under the field exp(a rho^2), 8-bit.
cv::Mat PanFrame(const cv::Mat& texture, cv::Size size, int t, double dx, double a) {
  cv::Mat f = texture(cv::Rect(static_cast<int>(t * dx), 0, size.width, size.height)).clone();
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      f.at<float>(y, x) *= static_cast<float>(
          std::exp(a * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy)));
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

// The fit over exact correspondences of a pan (a grid of points moved by
// the pan), with an exposure change each frame, recovers the field; without
// a field it finds none.
VignettingModel FitPan(double a, double exposure_step) {
  const cv::Size size(320, 180);
  const cv::Mat texture = Texture({320 + 20 * 12, 180}, 4);
  VignettingFit fit;
  for (int t = 1; t <= 12; ++t) {
    cv::Mat before = PanFrame(texture, size, t - 1, 20, a), after = PanFrame(texture, size, t, 20, a);
    after.convertTo(after, -1, 1 + exposure_step);
    std::vector<cv::Point2f> from, to;
    for (int y = 8; y < size.height - 8; y += 6)
      for (int x = 28; x < size.width - 8; x += 6) {
        from.emplace_back(static_cast<float>(x), static_cast<float>(y));
        to.emplace_back(static_cast<float>(x - 20), static_cast<float>(y));
      }
    fit.AddStep(before, after, 1.0, from, to, size);
  }
  EXPECT_GT(fit.pairs(), kMinVignettingPairs);
  return fit.Decide();
}

TEST(VignettingFit, FindsAFieldFromAPanAndNoneWithoutOne) {
  const VignettingModel m = FitPan(-0.3, 0.01);
  ASSERT_TRUE(m.found);
  EXPECT_NEAR(m.corner_gain(), std::exp(-0.3), 0.02);
  EXPECT_FALSE(FitPan(0, 0.01).found);
  // Brighter corners are the scene, not a lens.
  EXPECT_FALSE(FitPan(0.3, 0).found);
  // A weak field (2 % at the corner) is not worth correcting.
  EXPECT_FALSE(FitPan(std::log(0.98), 0).found);
}

TEST(VignettingFit, TooFewPairsDecideNothing) {
  VignettingFit fit;
  EXPECT_FALSE(fit.Decide().found);
  const cv::Mat flat(100, 100, CV_8U, cv::Scalar(100));
  // Points that do not move radially carry no evidence.
  fit.AddStep(flat, flat, 1.0, {{50, 50}, {10, 10}}, {{50, 50}, {10, 10}}, flat.size());
  EXPECT_EQ(fit.pairs(), 0u);
}

TEST(FlatField, UndoesTheFieldWithoutPassingWhite) {
  VignettingModel m;
  m.a = -0.3;
  m.found = true;
  const cv::Size size(64, 36);
  const cv::Mat gain = FlatFieldGain(m, size);
  double lo = 0, hi = 0;
  cv::minMaxLoc(gain, &lo, &hi);
  EXPECT_NEAR(hi, 1.0, 1e-6);
  EXPECT_NEAR(gain.at<float>(0, 0), 1.0, 1e-6);  // the corner keeps its level
  EXPECT_NEAR(gain.at<float>(18, 32), std::exp(-0.3), 0.01);  // the centre is darkened to it
  // A vignetted flat grey comes back flat (at the corner's level).
  cv::Mat grey = PanFrame(cv::Mat(size, CV_32F, cv::Scalar(200)), size, 0, 0, -0.3);
  const cv::Mat flat = FlatFielded(grey, gain);
  cv::minMaxLoc(flat, &lo, &hi);
  EXPECT_LE(hi - lo, 2);
  EXPECT_NEAR(lo, 200 * std::exp(-0.3), 2);
}

}  // namespace
}  // namespace hapcine
