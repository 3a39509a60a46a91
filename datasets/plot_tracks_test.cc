#include "datasets/plot_tracks.h"

#include <gtest/gtest.h>

#include <algorithm>

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
  CameraPlotOptions no_labels;
  no_labels.effect_labels = false;
  const Figure fig = CameraPathFigure(gt, &est, no_labels);
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

TEST(PlotTracksTest, CameraFigureShowsTheClassifiersEffectsPerPath) {
  // 1 s still, 3 s moving right at 1 m/s, 1 s still; the "estimate" moves left.
  auto path = [](double dir) {
    CameraPath p;
    for (int i = 0; i <= 150; ++i) {
      CameraFrame f;
      f.frame = i;
      f.time_s = i / 30.0;
      f.center.x() = dir * std::clamp(f.time_s - 1.0, 0.0, 3.0);
      f.fov_deg = 50;
      p.frames.push_back(f);
    }
    return p;
  };
  const CameraPath gt = path(1), est = path(-1);
  const Figure fig = CameraPathFigure(gt, &est);
  ASSERT_EQ(fig.panels.size(), 5u);
  const PlotPanel& g = fig.panels[3];
  const PlotPanel& e = fig.panels[4];
  EXPECT_FALSE(g.show_y_axis);
  EXPECT_NE(g.title.find("(GT)"), std::string::npos);
  ASSERT_EQ(g.bands.size(), 3u);
  EXPECT_EQ(g.bands[0].label, "none");
  EXPECT_EQ(g.bands[1].label, "traveling right");
  EXPECT_NEAR(g.bands[1].x_begin, 1.0, 0.3);
  EXPECT_NEAR(g.bands[1].x_end, 4.0, 0.3);
  EXPECT_NEAR(g.bands[2].x_end, 5.0 + 1 / 30.0, 1e-9);
  ASSERT_EQ(e.bands.size(), 3u);
  EXPECT_EQ(e.bands[1].label, "traveling left");
  // One colour per label across both rows; "none" is light grey.
  EXPECT_NE(g.bands[1].color.r + 256 * g.bands[1].color.g,
            e.bands[1].color.r + 256 * e.bands[1].color.g);
  EXPECT_EQ(g.bands[0].color.r, 235);
}

TEST(PlotTracksTest, EffectsOnBothSidesOfACutStayTwoBands) {
  CameraPath p;
  for (int i = 0; i <= 120; ++i) {  // two shots, each moving right for 1.5 s
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 30.0;
    f.shot = i <= 60 ? 0 : 1;
    f.center.x() = 10.0 * f.shot.value() + std::clamp(f.time_s - 2.0 * f.shot.value(), 0.0, 1.5);
    f.fov_deg = 50;
    p.frames.push_back(f);
  }
  const Figure fig = CameraPathFigure(p, nullptr);
  ASSERT_EQ(fig.panels.size(), 4u);
  int traveling = 0;
  for (const PlotBand& b : fig.panels[3].bands) traveling += b.label == "traveling right";
  EXPECT_EQ(traveling, 2);
}

TEST(PlotTracksTest, SeveralHapticTracksOverlayLikeFigure4) {
  HapticTrack a, b;
  a.model = "cinematic";
  b.model = "semantic";
  for (int i = 0; i < 100; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    s.pos_m[2] = Eigen::Vector3d(0, 0, -0.001 * i);
    a.samples.push_back(s);
    s.effect = i < 50 ? "none" : "zoom_in";
    b.samples.push_back(s);
  }
  const Figure fig = HapticTracksFigure({&a, &b}, "zoom_in");
  ASSERT_EQ(fig.panels.size(), 4u);  // three actuators + b's effect line
  ASSERT_EQ(fig.panels[2].series.size(), 6u);
  EXPECT_EQ(fig.panels[2].series[2].name, "z (cinematic)");
  EXPECT_FALSE(fig.panels[2].series[2].dashed);
  EXPECT_EQ(fig.panels[2].series[5].name, "z (semantic)");
  EXPECT_TRUE(fig.panels[2].series[5].dashed);
  EXPECT_NEAR(fig.panels[2].series[5].y[99], -99.0, 1e-9);
  EXPECT_EQ(fig.panels[3].title, "effect (semantic)");
  EXPECT_THROW(HapticTracksFigure({}), UsageError);
}

TEST(PlotTracksTest, CutsAndConfidenceComeFromTheShotAndConfidenceColumns) {
  CameraPath path = Path(50, 1.0, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(ShotCutTimes(path).empty());
  EXPECT_FALSE(ConfidencePanel(path, "c").has_value());
  for (auto& f : path.frames) {
    f.shot = f.frame < 20 ? 0 : f.frame < 35 ? 1 : 2;
    if (f.frame % 2 == 0) f.confidence = 0.5;  // lost or unmeasured frames read 0
  }
  EXPECT_EQ(ShotCutTimes(path), (std::vector<double>{20 / 25.0, 35 / 25.0}));
  const std::optional<PlotPanel> conf = ConfidencePanel(path, "c");
  ASSERT_TRUE(conf.has_value());
  EXPECT_TRUE(conf->series[0].filled);
  EXPECT_EQ(conf->series[0].y[0], 0.5);
  EXPECT_EQ(conf->series[0].y[1], 0.0);
  EXPECT_EQ(conf->y_max, 1.0);
  CameraPlotOptions opt;
  opt.effect_labels = false;
  const Figure fig = CameraPathFigure(path, nullptr, opt);
  ASSERT_EQ(fig.panels.size(), 4u);  // rotation, centre, FOV, confidence
  EXPECT_EQ(fig.cut_x.size(), 2u);

  HapticTrack track;
  for (int i = 0; i < 10; ++i) {
    HapticSample s;
    s.time_s = i * 0.01;
    if (i > 0) s.shot = i < 6 ? 3 : 4;  // a row without a shot is no cut
    track.samples.push_back(s);
  }
  EXPECT_EQ(ShotCutTimes(track), std::vector<double>{0.06});
  EXPECT_EQ(HapticTrackFigure(track).cut_x, std::vector<double>{0.06});
}

TEST(PlotTracksTest, EmptyInputsAreUsageErrors) {
  EXPECT_THROW(CameraPathFigure(CameraPath(), nullptr), UsageError);
  EXPECT_THROW(HapticTrackFigure(HapticTrack()), UsageError);
}

}  // namespace
}  // namespace hapcine
