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
}  // namespace hapcine::bench
