#include "datasets/plot_figure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(PlotFigureTest, NiceTicksAreRoundAndCoverTheRange) {
  const auto t = NiceTicks(0.0, 10.0, 5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_EQ(t.back(), 10.0);
  const auto u = NiceTicks(-0.013, 0.042, 6);
  ASSERT_GE(u.size(), 3u);
  EXPECT_NEAR(u[1] - u[0], 0.01, 1e-12);
  EXPECT_TRUE(NiceTicks(1, 1).empty());
  EXPECT_TRUE(NiceTicks(0, std::numeric_limits<double>::infinity()).empty());
}

TEST(PlotFigureTest, TickLabels) {
  EXPECT_EQ(TickLabel(2.5, 0.5), "2.5");
  EXPECT_EQ(TickLabel(10, 5), "10");
  EXPECT_EQ(TickLabel(-0.0, 1), "0");
  EXPECT_EQ(TickLabel(0.02, 0.01), "0.02");
}

TEST(PlotFigureTest, FlatAndEmptyDataGetAUsableRange) {
  Figure fig;
  PlotPanel p;
  PlotSeries s;
  s.x = {0, 1, 2};
  s.y = {5, 5, 5};
  p.series.push_back(s);
  fig.panels.push_back(p);
  fig.panels.push_back(PlotPanel());  // no data at all
  const FigureLayout L = LayoutFigure(fig);
  EXPECT_LT(L.panels[0].y_min, 5);
  EXPECT_GT(L.panels[0].y_max, 5);
  EXPECT_LT(L.panels[1].y_min, L.panels[1].y_max);
  EXPECT_TRUE(std::isfinite(L.panels[0].MapY(5)));
  EXPECT_GT(L.height_px, 0);
}

TEST(PlotFigureTest, BadFiguresAreUsageErrors) {
  EXPECT_THROW(LayoutFigure(Figure()), UsageError);
  Figure fig;
  PlotPanel p;
  PlotSeries s;
  s.x = {0, 1};
  s.y = {0};
  p.series.push_back(s);
  fig.panels.push_back(p);
  EXPECT_THROW(LayoutFigure(fig), UsageError);
}

TEST(PlotFigureTest, NonFinitePointsSplitRunsAndLongRunsAreDecimated) {
  Figure fig;
  PlotPanel p;
  PlotSeries s;
  for (int i = 0; i < 100000; ++i) {
    s.x.push_back(i * 1e-3);
    s.y.push_back(i == 50000 ? std::nan("") : std::sin(i * 1e-2));
  }
  p.series.push_back(s);
  fig.panels.push_back(p);
  const FigureLayout L = LayoutFigure(fig);
  const auto runs = SeriesRuns(s, L, L.panels[0].plot, 8000);
  ASSERT_EQ(runs.size(), 2u);
  for (const auto& r : runs) {
    EXPECT_LE(r.size(), 4 * static_cast<size_t>(L.panels[0].plot.w) + 8);
    EXPECT_GT(r.size(), 100u);
  }
  // The envelope keeps the extremes.
  double mx = -1;
  for (const auto& [x, y] : runs[0]) mx = std::max(mx, y);
  EXPECT_NEAR(mx, 1.0, 1e-3);
  EXPECT_EQ(SeriesRuns(s, L, L.panels[0].plot, 1u << 30)[0].size(), 50000u);
}

TEST(PlotFigureTest, BandLabelsThatDoNotFitAreSkipped) {
  EXPECT_TRUE(BandLabelFits("none", 40));
  EXPECT_FALSE(BandLabelFits("none", 20));
  EXPECT_FALSE(BandLabelFits("", 1000));
}

TEST(PlotFigureTest, LegendWidensForLongNamesUpToAThird) {
  Figure fig;
  fig.panels.resize(1);
  PlotSeries s;
  s.x = {0, 1};
  s.y = {0, 1};
  s.name = "x";
  fig.panels[0].series.push_back(s);
  const FigureLayout narrow = LayoutFigure(fig);
  fig.panels[0].series[0].name = std::string(60, 'n');
  const FigureLayout wide = LayoutFigure(fig);
  EXPECT_LT(wide.legend_x, narrow.legend_x);
  EXPECT_LT(wide.panels[0].plot.w, narrow.panels[0].plot.w);
  fig.panels[0].series[0].name = std::string(1000, 'n');
  EXPECT_NEAR(LayoutFigure(fig).legend_x, fig.width_px * 2.0 / 3 + 10, 1e-9);
}

TEST(PlotFigureTest, CropKeepsOnePointBeyondEachEdgeAndCutsBandsAndCuts) {
  Figure fig;
  fig.panels.resize(2);
  PlotSeries s;
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i);
    s.y.push_back(i * i);
  }
  fig.panels[0].series.push_back(s);
  fig.panels[1].bands = {{0, 20, "pan"}, {20, 50, "zoom"}, {50, 100, "pan"}};
  fig.cut_x = {20, 50};
  const Figure page = CropFigure(fig, 30.5, 60);
  const PlotSeries& kept = page.panels[0].series[0];
  ASSERT_EQ(kept.x.size(), 32u);  // 30 .. 61
  EXPECT_EQ(kept.x.front(), 30);
  EXPECT_EQ(kept.x.back(), 61);
  EXPECT_EQ(kept.y.back(), 61 * 61);
  ASSERT_EQ(page.panels[1].bands.size(), 2u);
  EXPECT_EQ(page.panels[1].bands[0].x_begin, 30.5);
  EXPECT_EQ(page.panels[1].bands[1].x_end, 60);
  EXPECT_EQ(page.cut_x, std::vector<double>{50});
  const FigureLayout L = LayoutFigure(page);
  EXPECT_EQ(L.x_min, 30.5);
  EXPECT_EQ(L.x_max, 60);
  // A range between two points still keeps the line through it.
  EXPECT_EQ(CropFigure(fig, 40.2, 40.7).panels[0].series[0].x, (std::vector<double>{40, 41}));
  EXPECT_THROW(CropFigure(fig, 5, 5), UsageError);
}

TEST(PlotFigureTest, LegendNamesSeriesBandColoursAndCuts) {
  Figure fig;
  fig.panels.resize(2);
  PlotSeries s;
  s.x = {0, 1};
  s.y = {0, 1};
  s.name = "x";
  fig.panels[0].series.push_back(s);
  fig.panels[1].bands = {{0, 0.3, "pan", PaletteColor(1)}, {0.3, 0.5, "zoom", PaletteColor(2)},
                         {0.5, 1, "pan", PaletteColor(1)}};
  EXPECT_EQ(PanelLegend(fig, 0).size(), 1u);
  fig.cut_x = {0.5};
  const std::vector<LegendEntry> first = PanelLegend(fig, 0);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[1].name, "cut");
  EXPECT_EQ(first[1].kind, LegendEntry::kCut);
  const std::vector<LegendEntry> bands = PanelLegend(fig, 1);
  ASSERT_EQ(bands.size(), 2u);  // each label once
  EXPECT_EQ(bands[0].name, "pan");
  EXPECT_EQ(bands[1].kind, LegendEntry::kSwatch);
  EXPECT_EQ(bands[1].color.g, PaletteColor(2).g);
}

}  // namespace
}  // namespace hapcine
