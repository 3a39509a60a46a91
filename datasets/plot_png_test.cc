#include "datasets/plot_png.h"

#include <gtest/gtest.h>

#include <cstdio>
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
