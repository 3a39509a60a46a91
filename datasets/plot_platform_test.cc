#include "datasets/plot_platform.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "datasets/svg_writer.h"

namespace hapcine {
namespace {

PlatformTrack Track(bool legs, double heave_m) {
  PlatformTrack t;
  t.platform = "test";
  for (int i = 0; i < 100; ++i) {
    PlatformSample s;
    s.time_s = i * 0.01;
    s.pose[1] = heave_m * i / 100;  // heave only
    s.pose[5] = 0.01 * i / 100;     // and roll
    if (legs) s.legs = LegLengths{0.5 + s.pose[1], 0.5, 0.5, 0.5, 0.5, 0.5};
    t.samples.push_back(s);
  }
  return t;
}

TEST(PlotPlatform, PanelsForPoseAndLegsOnlyForWhatMoves) {
  const PlatformTrack stewart = Track(true, 0.05), seat = Track(false, 0.02);
  const Figure fig = PlatformTracksFigure({&stewart, &seat}, "t", {"stewart", "seat"});
  ASSERT_EQ(fig.panels.size(), 3u);  // translation, rotation, legs
  // Heave of both tracks (DOFs that stay 0 are left out), the second dashed.
  ASSERT_EQ(fig.panels[0].series.size(), 2u);
  EXPECT_EQ(fig.panels[0].series[0].name, "heave y (stewart)");
  EXPECT_TRUE(fig.panels[0].series[1].dashed);
  EXPECT_NEAR(fig.panels[0].series[0].y.back(), 1000 * 0.05 * 99 / 100, 1e-9);  // mm
  EXPECT_EQ(fig.panels[1].series.size(), 2u);  // roll, in degrees
  EXPECT_NEAR(fig.panels[1].series[0].y.back(), 0.01 * 99 / 100 * 180 / 3.14159265358979, 1e-9);
  EXPECT_EQ(fig.panels[2].series.size(), 6u);  // the Stewart track's six legs
  EXPECT_NEAR(fig.panels[2].series[0].y.back(), 1000 * 0.05 * 99 / 100, 1e-9);
  EXPECT_FALSE(RenderFigureSvg(fig).empty());
}

TEST(PlotPlatform, RejectsEmptyInput) {
  EXPECT_THROW(PlatformTracksFigure({}), UsageError);
  PlatformTrack empty;
  EXPECT_THROW(PlatformTracksFigure({&empty}), UsageError);
}

}  // namespace
}  // namespace hapcine
