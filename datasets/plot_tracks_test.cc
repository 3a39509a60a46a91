#include "datasets/plot_tracks.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/rotation.h"
#include "datasets/svg_writer.h"

namespace hapcine {
namespace {

CameraPath Path(int n, double scale, const Eigen::Quaterniond& world) {
  CameraPath p;
  for (int i = 0; i < n; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 25.0;
    f.center = world * Eigen::Vector3d(scale * 0.01 * i, 0, 0) + Eigen::Vector3d(1, 2, 3);
    f.world_from_cam = world * QuaternionFromPanTiltRoll({1.0 * i, 0.5 * i, 0});
    f.fov_deg = 50 + 0.1 * i;
    p.frames.push_back(f);
  }
  return p;
}

TEST(PlotTracksTest, CameraFigureOverlaysEstimateRelativeAndScaled) {
  const CameraPath gt = Path(30, 1.0, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY())));
  const CameraPath est = Path(30, 4.0, Eigen::Quaterniond::Identity());
  const Figure fig = CameraPathFigure(gt, &est);
  ASSERT_EQ(fig.panels.size(), 3u);
  ASSERT_EQ(fig.panels[0].series.size(), 6u);  // pan/tilt/roll x (GT, est)
  const PlotSeries& pan_gt = fig.panels[0].series[0];
  const PlotSeries& pan_est = fig.panels[0].series[3];
  EXPECT_TRUE(pan_est.dashed);
  for (size_t i = 0; i < 30; ++i) EXPECT_NEAR(pan_gt.y[i], pan_est.y[i], 1e-9);
  const PlotSeries& x_gt = fig.panels[1].series[0];
  const PlotSeries& x_est = fig.panels[1].series[3];
  for (size_t i = 0; i < 30; ++i) EXPECT_NEAR(x_gt.y[i], x_est.y[i], 1e-9);
  EXPECT_NE(x_est.name.find("x0.25"), std::string::npos) << x_est.name;
  EXPECT_EQ(fig.panels[2].series[0].y[10], 51.0);
}

TEST(PlotTracksTest, HapticFigureHasThreeActuatorsAndEffectBands) {
  HapticTrack track;
  track.rate_hz = 100;
  for (int i = 0; i < 300; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    s.pos_m[0] = Eigen::Vector3d(0.01, 0, 0);
    if (i >= 50 && i < 150) s.effect = "pan";
    if (i >= 200) s.effect = "zoom";
    track.samples.push_back(s);
  }
  const Figure fig = HapticTrackFigure(track, "t");
  ASSERT_EQ(fig.panels.size(), 4u);
  EXPECT_EQ(fig.panels[0].series.size(), 3u);
  EXPECT_NEAR(fig.panels[0].series[0].y[0], 10.0, 1e-12);  // millimetres
  ASSERT_EQ(fig.panels[3].bands.size(), 2u);
  EXPECT_EQ(fig.panels[3].bands[0].label, "pan");
  EXPECT_NEAR(fig.panels[3].bands[0].x_begin, 0.5, 1e-12);
  EXPECT_NEAR(fig.panels[3].bands[0].x_end, 1.5, 1e-12);
  EXPECT_NEAR(fig.panels[3].bands[1].x_end, 3.0, 1e-12);
  const std::string svg = RenderFigureSvg(fig);
  EXPECT_NE(svg.find(">zoom</text>"), std::string::npos);

  track.samples[0].effect.reset();
  for (auto& s : track.samples) s.effect.reset();
  EXPECT_EQ(HapticTrackFigure(track).panels.size(), 3u);
}

TEST(PlotTracksTest, EmptyInputsAreUsageErrors) {
  EXPECT_THROW(CameraPathFigure(CameraPath(), nullptr), UsageError);
  EXPECT_THROW(HapticTrackFigure(HapticTrack()), UsageError);
}

}  // namespace
}  // namespace hapcine
