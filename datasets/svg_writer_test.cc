#include "datasets/svg_writer.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace hapcine {
namespace {

Figure TwoPanelFigure() {
  Figure fig;
  fig.title = "A & B <test>";
  PlotPanel a;
  a.title = "angles";
  PlotSeries s;
  s.name = "pan";
  for (int i = 0; i < 37; ++i) {
    s.x.push_back(i * 0.1);
    s.y.push_back(i * i);
  }
  a.series.push_back(s);
  s.name = "est";
  s.dashed = true;
  s.y.assign(37, 3.0);
  a.series.push_back(s);
  PlotPanel b;
  b.show_y_axis = false;
  b.bands.push_back({0.5, 1.5, "shake", PaletteColor(3)});
  fig.panels = {a, b};
  return fig;
}

std::vector<size_t> PolylinePointCounts(const std::string& svg) {
  std::vector<size_t> counts;
  const std::regex re("<polyline[^>]*points=\"([^\"]*)\"");
  for (std::sregex_iterator it(svg.begin(), svg.end(), re), end; it != end; ++it) {
    std::istringstream pts((*it)[1].str());
    std::string p;
    size_t n = 0;
    while (pts >> p) {
      EXPECT_NE(p.find(','), std::string::npos);
      ++n;
    }
    counts.push_back(n);
  }
  return counts;
}

TEST(SvgWriterTest, WellFormedWithOnePolylinePerSeries) {
  const std::string svg = RenderFigureSvg(TwoPanelFigure());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>\n"), std::string::npos);
  EXPECT_EQ(PolylinePointCounts(svg), (std::vector<size_t>{37, 37}));
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  // Text is escaped; no raw '&' outside entities.
  EXPECT_NE(svg.find("A &amp; B &lt;test&gt;"), std::string::npos);
  EXPECT_EQ(std::regex_search(svg, std::regex("&(?!amp;|lt;|gt;|quot;)")), false);
  EXPECT_NE(svg.find(">shake</text>"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  // Balanced elements: every <g> closed.
  size_t open = 0, close = 0;
  for (size_t p = svg.find("<g"); p != std::string::npos; p = svg.find("<g", p + 1)) ++open;
  for (size_t p = svg.find("</g>"); p != std::string::npos; p = svg.find("</g>", p + 1)) ++close;
  EXPECT_EQ(open, close);
}

TEST(SvgWriterTest, GapInDataSplitsThePolyline) {
  Figure fig = TwoPanelFigure();
  fig.panels[0].series.resize(1);
  fig.panels[0].series[0].y[10] = std::nan("");
  EXPECT_EQ(PolylinePointCounts(RenderFigureSvg(fig)), (std::vector<size_t>{10, 26}));
}

TEST(SvgWriterTest, FileIsWrittenAtomically) {
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/svg_writer_test.svg";
  WriteFigureSvgFile(TwoPanelFigure(), file);
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), RenderFigureSvg(TwoPanelFigure()));
  std::remove(file.c_str());
}

}  // namespace
}  // namespace hapcine
