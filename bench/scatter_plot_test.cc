#include "bench/scatter_plot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace hapcine::bench {
namespace {

TEST(AxisTicks, LinearAndLog) {
  EXPECT_EQ(AxisTicks(0, 10, false), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(AxisTicks(0.5, 30, true), (std::vector<double>{0.5, 1, 2, 5, 10, 20}));
  // Many decades: powers of ten only.
  EXPECT_EQ(AxisTicks(1e-3, 1e3, true), (std::vector<double>{1e-3, 1e-2, 1e-1, 1, 10, 100, 1000}));
}

TEST(RenderScatter, DrawsPointsAndSkipsUnplottable) {
  ScatterChart c;
  c.log_x = c.log_y = true;
  ScatterSeries s;
  s.name = "a";
  s.x = {1, 10, -1, NAN};
  s.y = {0.1, 1, 1, 1};
  s.line = true;
  c.series = {s};
  const cv::Mat img = RenderScatter(c);
  EXPECT_EQ(img.cols, c.width_px);
  EXPECT_EQ(img.rows, c.height_px);
  EXPECT_LT(cv::mean(img)[0], 255);  // something was drawn
}

TEST(RenderScatter, NothingToDrawIsAnError) {
  ScatterChart c;
  c.log_y = true;
  ScatterSeries s;
  s.x = {1};
  s.y = {0};  // not plottable on a log axis
  c.series = {s};
  EXPECT_THROW(RenderScatter(c), Error);
  c.series[0].x = {1, 2};
  EXPECT_THROW(RenderScatter(c), Error);  // mismatched lengths
}

}  // namespace
TEST(PlaceLabels, NeighboursDoNotOverlap) {
  // Two settings with the same error 40 px apart, and a third on top of the first.
  const std::vector<cv::Point> anchors{{100, 200}, {140, 200}, {102, 201}};
  const std::vector<cv::Size> sizes(3, cv::Size(120, 10));
  const std::vector<cv::Rect> boxes = PlaceLabels(anchors, sizes, cv::Rect(0, 0, 900, 560));
  ASSERT_EQ(boxes.size(), 3u);
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j) EXPECT_EQ((boxes[i] & boxes[j]).area(), 0) << i << " " << j;
  // The first keeps the usual place: upper right of its point.
  EXPECT_EQ(boxes[0], cv::Rect(108, 184, 120, 10));
}

TEST(PlaceLabels, StaysInsideAndFallsBackWhenCrowded) {
  // Near the right edge the label goes to the left.
  const auto edge = PlaceLabels({{880, 200}}, {cv::Size(100, 10)}, cv::Rect(0, 0, 900, 560));
  EXPECT_LT(edge[0].x + edge[0].width, 880);
  // No free place at all: the upper right, not nothing.
  const auto crowded = PlaceLabels({{5, 5}}, {cv::Size(100, 10)}, cv::Rect(0, 0, 20, 20));
  ASSERT_EQ(crowded.size(), 1u);
  EXPECT_EQ(crowded[0], cv::Rect(13, -11, 100, 10));
  EXPECT_TRUE(PlaceLabels({}, {}, cv::Rect(0, 0, 10, 10)).empty());
}

}  // namespace hapcine::bench
