#include "datasets/plot_png.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"

namespace hapcine {
namespace {

Figure SineFigure() {
  Figure fig;
  fig.width_px = 800;
  fig.panel_height_px = 200;
  PlotPanel p;
  PlotSeries s;
  s.name = "sin";
  s.color = {255, 0, 0};
  for (int i = 0; i <= 200; ++i) {
    s.x.push_back(i * 0.05);
    s.y.push_back(std::sin(i * 0.05));
  }
  p.series.push_back(s);
  s.dashed = true;
  s.color = {0, 0, 255};
  for (auto& y : s.y) y = -y;
  p.series.push_back(s);
  p.bands.push_back({2, 3, "band", {0, 255, 0}});
  fig.panels = {p, p};
  return fig;
}

TEST(PlotPngTest, ImageHasLayoutSizeAndDrawnSeries) {
  const Figure fig = SineFigure();
  const cv::Mat img = RenderFigurePng(fig);
  const FigureLayout L = LayoutFigure(fig);
  EXPECT_EQ(img.cols, 800);
  EXPECT_EQ(img.rows, L.height_px);
  EXPECT_EQ(img.type(), CV_8UC3);
  // Some strongly red (series 1, BGR) and blue (series 2) pixels exist.
  int red = 0, blue = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (p[2] > 200 && p[1] < 80 && p[0] < 80) ++red;
      if (p[0] > 200 && p[1] < 80 && p[2] < 80) ++blue;
    }
  }
  EXPECT_GT(red, 200);
  EXPECT_GT(blue, 100);
  EXPECT_LT(blue, red);  // dashed draws less ink
}

// Pixels of exactly CutLineColor() in each image column.
std::vector<int> CutPixelsPerColumn(const cv::Mat& img) {
  const PlotColor c = CutLineColor();
  std::vector<int> per_column(static_cast<size_t>(img.cols), 0);
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (p[0] == c.b && p[1] == c.g && p[2] == c.r) ++per_column[static_cast<size_t>(x)];
    }
  }
  return per_column;
}

TEST(PlotPngTest, CutLinesCrossEveryPanelInTheirOwnColour) {
  Figure fig = SineFigure();
  fig.cut_x = {4.0};
  const FigureLayout L = LayoutFigure(fig);
  const std::string file = ::testing::TempDir() + "/cut_plot.png";
  WriteFigurePngFile(fig, file);
  const cv::Mat img = cv::imread(file, cv::IMREAD_COLOR);
  ASSERT_EQ(img.cols, 800);
  ASSERT_EQ(img.rows, L.height_px);
  const std::vector<int> cut = CutPixelsPerColumn(img);
  const int at = static_cast<int>(std::lround(L.MapX(L.panels[0].plot, 4.0)));
  // Both panels' data areas, top to bottom (2 px wide: columns at and beside).
  const double expected = L.panels[0].plot.h + L.panels[1].plot.h - 4;
  EXPECT_GE(cut[at] + cut[at + 1] + cut[at - 1], expected);
  // Nowhere else in the data area: the legend's "cut" mark sits right of it.
  const int right_edge = static_cast<int>(L.panels[0].plot.x + L.panels[0].plot.w);
  for (int x = 0; x < right_edge; ++x) {
    if (std::abs(x - at) > 1) {
      EXPECT_EQ(cut[x], 0) << x;
    }
  }
  int legend = 0;
  for (int x = right_edge + 1; x < img.cols; ++x) legend += cut[x];
  EXPECT_GT(legend, 0);
  std::remove(file.c_str());

  const cv::Mat without = RenderFigurePng(CropFigure(fig, 0, 3.5));  // the cut is outside
  for (int n : CutPixelsPerColumn(without)) EXPECT_EQ(n, 0);
}

TEST(PlotPngTest, AFilledSeriesShadesDownToZero) {
  Figure fig;
  fig.width_px = 600;
  PlotPanel p;
  PlotSeries s;
  s.x = {0, 10};
  s.y = {0.8, 0.8};
  s.color = {0, 0, 255};
  s.filled = true;
  p.series.push_back(s);
  p.y_min = 0;
  p.y_max = 1;
  fig.panels = {p};
  const FigureLayout L = LayoutFigure(fig);
  const cv::Mat img = RenderFigurePng(fig);
  const PanelLayout& pl = L.panels[0];
  const int x = static_cast<int>(L.MapX(pl.plot, 5));
  const cv::Vec3b under = img.at<cv::Vec3b>(static_cast<int>(pl.MapY(0.4)), x);
  const cv::Vec3b above = img.at<cv::Vec3b>(static_cast<int>(pl.MapY(0.9)), x);
  EXPECT_LT(under[2], 230);  // blue blended over white: less red
  EXPECT_GT(under[0], 240);
  EXPECT_EQ(above, cv::Vec3b(255, 255, 255));
}

TEST(PlotPngTest, WrittenFileReadsBack) {
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/plot_png_test.png";
  WriteFigurePngFile(SineFigure(), file);
  const cv::Mat back = cv::imread(file);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(back.cols, 800);
  EXPECT_EQ(back.rows, LayoutFigure(SineFigure()).height_px);
  std::remove(file.c_str());
}

TEST(PlotPngTest, UnwritableDirectoryIsAnError) {
  EXPECT_THROW(WriteFigurePngFile(SineFigure(), "/nonexistent-dir/x.png"), Error);
}

}  // namespace
}  // namespace hapcine
