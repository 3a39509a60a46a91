#include "extract/pyramid_lk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <vector>

#include "core/error.h"
#include "extract/test_frames.h"

namespace hapcine {
namespace {

struct Pair {
  std::vector<cv::Mat> from_pyramid, to_pyramid;
  std::vector<cv::Point2f> points;
};

// A textured picture and the same picture moved by (dx, dy) (warpAffine,
// so sub-pixel and not exactly a shift: the trackers must agree, not be
// right), with points on a grid, some near and some beyond the borders.
Pair MakePair(double dx, double dy, cv::Size window, int max_level) {
  cv::Mat gray;
  cv::cvtColor(testing::NoiseTexture({480, 320}, 7), gray, cv::COLOR_BGR2GRAY);
  cv::Mat moved;
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::warpAffine(gray, moved, m, gray.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  Pair p;
  cv::buildOpticalFlowPyramid(gray, p.from_pyramid, window, max_level, true);
  cv::buildOpticalFlowPyramid(moved, p.to_pyramid, window, max_level, true);
  for (float y = -3.5f; y < 330; y += 13.25f)
    for (float x = -2.25f; x < 490; x += 11.5f) p.points.emplace_back(x, y);
  return p;
}

// OpenCV's one call, as the tracker made it before the split.
void OneCall(const Pair& p, const PyramidLkOptions& o, std::vector<cv::Point2f>* to,
             std::vector<unsigned char>* status, bool initial = false) {
  cv::calcOpticalFlowPyrLK(p.from_pyramid, p.to_pyramid, p.points, *to, *status, cv::noArray(),
                           o.window, o.max_level, o.fine,
                           initial ? cv::OPTFLOW_USE_INITIAL_FLOW : 0);
}

TEST(PyramidLkTest, SameCriteriaGiveOpenCvsAnswerBitForBit) {
  for (int max_level : {0, 1, 3}) {
    PyramidLkOptions o;
    o.max_level = max_level;
    const Pair p = MakePair(9.3, -6.7, o.window, max_level);
    std::vector<cv::Point2f> want, got;
    std::vector<unsigned char> want_ok, got_ok;
    OneCall(p, o, &want, &want_ok);
    PyramidLk(p.from_pyramid, p.to_pyramid, p.points, &got, &got_ok, o);
    ASSERT_EQ(got.size(), want.size());
    int tracked = 0;
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_EQ(got_ok[i], want_ok[i]) << i;
      EXPECT_EQ(got[i].x, want[i].x) << i << " level " << max_level;  // exact, not near
      EXPECT_EQ(got[i].y, want[i].y) << i << " level " << max_level;
      tracked += want_ok[i] != 0;
    }
    EXPECT_GT(tracked, 300);
  }
}

TEST(PyramidLkTest, InitialFlowIsExactToo) {
  PyramidLkOptions o;
  const Pair p = MakePair(-14.6, 3.1, o.window, o.max_level);
  std::vector<cv::Point2f> want(p.points.size()), got;
  for (size_t i = 0; i < p.points.size(); ++i) want[i] = p.points[i] + cv::Point2f(-12, 2);
  got = want;
  std::vector<unsigned char> want_ok, got_ok;
  OneCall(p, o, &want, &want_ok, true);
  PyramidLk(p.from_pyramid, p.to_pyramid, p.points, &got, &got_ok, o, true);
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got_ok[i], want_ok[i]) << i;
    EXPECT_EQ(got[i], want[i]) << i;
  }
}

// The looser coarse criterion only seeds level 0, which converges to the
// same answer to within its own tolerance.
TEST(PyramidLkTest, LooseCoarseLevelsChangeTheAnswerByHundredthsOfAPixel) {
  PyramidLkOptions exact;
  PyramidLkOptions loose;
  loose.coarse = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.1);
  for (double d : {2.0, 17.0, 40.0}) {
    const Pair p = MakePair(d, -0.6 * d, exact.window, exact.max_level);
    std::vector<cv::Point2f> a, b;
    std::vector<unsigned char> a_ok, b_ok;
    PyramidLk(p.from_pyramid, p.to_pyramid, p.points, &a, &a_ok, exact);
    PyramidLk(p.from_pyramid, p.to_pyramid, p.points, &b, &b_ok, loose);
    int both = 0, right = 0, far = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a_ok[i] || !b_ok[i]) continue;
      ++both;
      // Interior points, before and after the move (the warp's border rows
      // are not a shift).
      const cv::Point2f q = p.points[i], r(q.x + d, q.y - 0.6 * d);
      if (std::min({q.x, q.y, r.x, r.y}) < 30 || std::max(q.x, r.x) > 450 ||
          std::max(q.y, r.y) > 290)
        continue;
      if (cv::norm(a[i] - cv::Point2f(r)) > 0.1) continue;  // OpenCV itself lost it
      ++right;
      far += cv::norm(a[i] - b[i]) > 0.03;
    }
    EXPECT_GT(both, 300) << d;
    EXPECT_GT(right, 150) << d;
    EXPECT_EQ(far, 0) << d;
  }
}

TEST(PyramidLkTest, DegenerateInputs) {
  PyramidLkOptions o;
  const Pair p = MakePair(1, 1, o.window, o.max_level);
  std::vector<cv::Point2f> to{{1, 1}};
  std::vector<unsigned char> ok{1};
  PyramidLk(p.from_pyramid, p.to_pyramid, {}, &to, &ok, o);
  EXPECT_TRUE(to.empty());
  EXPECT_TRUE(ok.empty());
  // A flat picture: nothing to track, every status false, no NaN trouble.
  std::vector<cv::Mat> flat;
  cv::buildOpticalFlowPyramid(cv::Mat(64, 64, CV_8UC1, cv::Scalar(90)), flat, o.window, 3, true);
  PyramidLk(flat, flat, {{30.f, 30.f}, {10.f, 50.f}}, &to, &ok, o);
  ASSERT_EQ(ok.size(), 2u);
  EXPECT_EQ(ok[0], 0);
  EXPECT_EQ(ok[1], 0);
  // Pyramids without derivatives, and initial flow of the wrong length.
  std::vector<cv::Mat> plain;
  cv::buildOpticalFlowPyramid(cv::Mat(64, 64, CV_8UC1, cv::Scalar(90)), plain, o.window, 0, false);
  EXPECT_THROW(PyramidLk(plain, plain, {{30.f, 30.f}}, &to, &ok, o), Error);
  to.assign(3, {0, 0});
  EXPECT_THROW(PyramidLk(flat, flat, {{30.f, 30.f}}, &to, &ok, o, true), Error);
}

}  // namespace
}  // namespace hapcine
