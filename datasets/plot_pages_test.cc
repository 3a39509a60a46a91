#include "datasets/plot_pages.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(PlotPagesTest, ParsesSecondsAndRunningTime) {
  EXPECT_EQ(ParsePlotTime("90", "--from"), 90);
  EXPECT_EQ(ParsePlotTime("90.5", "--from"), 90.5);
  EXPECT_EQ(ParsePlotTime("1:30", "--from"), 90);
  EXPECT_EQ(ParsePlotTime("1:02:03.5", "--from"), 3723.5);
  EXPECT_EQ(ParsePlotTime("0", "--from"), 0);
  for (const char* bad : {"", "-3", "1:60", "1:2:3:4", "1.5:00", "abc", "1:", ":30", "nan", "1e999"}) {
    EXPECT_THROW(ParsePlotTime(bad, "--to"), UsageError) << bad;
  }
}

TEST(PlotPagesTest, TwoHoursInTenMinutePagesIsTwelvePages) {
  const std::vector<TimeRange> pages = PagesByDuration(0, 7199.99, 600);
  ASSERT_EQ(pages.size(), 12u);  // the 0.01 s remainder joins the last page
  EXPECT_EQ(pages.front().first, 0);
  EXPECT_EQ(pages.back().second, 7199.99);
  for (size_t i = 1; i < pages.size(); ++i) EXPECT_EQ(pages[i].first, pages[i - 1].second);
  EXPECT_EQ(PagesByDuration(0, 7210, 600).size(), 13u);
  EXPECT_EQ(PagesByDuration(5, 20, 0).size(), 1u);
  // Degenerate: a single instant still gives a drawable page.
  const std::vector<TimeRange> one = PagesByDuration(3, 3, 600);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_GT(one[0].second, one[0].first);
}

TEST(PlotPagesTest, OnePagePerShotInsideTheRange) {
  const std::vector<TimeRange> pages = PagesByShot(1, 10, {0.5, 2, 2, 5, 10, 12});
  ASSERT_EQ(pages.size(), 3u);
  EXPECT_EQ(pages[0], TimeRange(1, 2));
  EXPECT_EQ(pages[1], TimeRange(2, 5));
  EXPECT_EQ(pages[2], TimeRange(5, 10));
  EXPECT_EQ(PagesByShot(0, 4, {}).size(), 1u);
}

TEST(PlotPagesTest, PageFilesAreNumberedBeforeTheExtension) {
  EXPECT_EQ(PagePath("out/fig.png", 0, 1), "out/fig.png");
  EXPECT_EQ(PagePath("out/fig.png", 0, 3), "out/fig-001.png");
  EXPECT_EQ(PagePath("out/fig.svg", 11, 12), "out/fig-012.svg");
  EXPECT_EQ(PagePath("out.d/fig", 1, 2), "out.d/fig-002");
}

}  // namespace
}  // namespace hapcine
