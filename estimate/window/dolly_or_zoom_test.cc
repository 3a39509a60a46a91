#include "estimate/window/dolly_or_zoom.h"

#include <gtest/gtest.h>

#include <cmath>

#include "estimate/window/window_test_scene.h"

namespace hapcine {
namespace {

WindowKeyframe Keyframe(MotionModel m, bool fixed = false, bool chain_start = false) {
  WindowKeyframe k;
  k.model = m;
  k.fixed = fixed;
  k.chain_start = chain_start;
  return k;
}

TEST(DollyOrZoom, LabelsTurnEveryMovingFreeIntervalIntoGeneral) {
  using M = MotionModel;
  const std::vector<WindowKeyframe> kf{Keyframe(M::kStatic, true), Keyframe(M::kZoom, true),
                                       Keyframe(M::kStatic),       Keyframe(M::kZoom),
                                       Keyframe(M::kRotation),     Keyframe(M::kRotationZoom),
                                       Keyframe(M::kZoom, false, true)};
  const std::vector<M> labels = DollyLabels(kf);
  // Held and static intervals and a chain's start keep their labels.
  EXPECT_EQ(labels, (std::vector<M>{M::kStatic, M::kZoom, M::kStatic, M::kGeneral, M::kGeneral, M::kGeneral,
                                    M::kZoom}));
}

TEST(DollyOrZoom, NoLabelsWithoutAZoomOrWithTranslation) {
  using M = MotionModel;
  EXPECT_TRUE(DollyLabels({Keyframe(M::kStatic), Keyframe(M::kRotation), Keyframe(M::kStatic)}).empty());
  EXPECT_TRUE(DollyLabels({Keyframe(M::kStatic), Keyframe(M::kZoom), Keyframe(M::kGeneral)}).empty());
  EXPECT_TRUE(DollyLabels({Keyframe(M::kStatic), Keyframe(M::kZoom, true)}).empty());  // only a held zoom
  EXPECT_TRUE(DollyLabels({}).empty());
  EXPECT_TRUE(DollyLabels({Keyframe(M::kZoom)}).empty());  // the first keyframe has no interval
}

TEST(DollyOrZoom, StartMovesEachCameraSoThatAPointAtTheDepthScalesAsTheZoom) {
  std::vector<BaCamera> zoom(3);
  zoom[1].log_focal = std::log(1.25);
  zoom[2].log_focal = std::log(0.8);  // zoomed out: a pull-back
  zoom[2].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  zoom[1].rotation_source = 0;
  const std::vector<BaCamera> start = DollyStart(std::vector<BaCamera>(3), zoom, 0, 2.0);
  // Z / (Z - t) = 1.25 at Z = 2: t = 0.4 along the axis.
  EXPECT_NEAR((start[1].center - Eigen::Vector3d(0, 0, 0.4)).norm(), 0, 1e-12);
  EXPECT_EQ(start[1].rotation_source, 0);  // the zoom shared its rotation: the dolly too
  // 0.8: t = -0.5 along camera 2's own (turned) axis.
  EXPECT_NEAR((start[2].center - zoom[2].world_from_cam * Eigen::Vector3d(0, 0, -0.5)).norm(), 0, 1e-12);
  EXPECT_TRUE(start[2].world_from_cam.isApprox(zoom[2].world_from_cam));
  for (const BaCamera& c : start) EXPECT_EQ(c.log_focal, 0.0);  // the held keyframe's focal
  // A held pivot after the first keyframe: the cameras up to it are kept.
  std::vector<BaCamera> shared(3);
  shared[1].center = Eigen::Vector3d(5, 0, 0);
  const std::vector<BaCamera> held = DollyStart(shared, zoom, 1, 2.0);
  EXPECT_EQ(held[1].center, Eigen::Vector3d(5, 0, 0));
  EXPECT_EQ(DollyStart(shared, zoom, 7, 2.0)[2].center, Eigen::Vector3d::Zero());  // no such pivot
}

TEST(DollyOrZoom, ExtraParametersCountCentresDepthsLessZoomsAndTheScale) {
  using M = MotionModel;
  const std::vector<M> zoom{M::kStatic, M::kZoom, M::kRotation, M::kStatic};
  const std::vector<M> dolly{M::kStatic, M::kGeneral, M::kGeneral, M::kStatic};
  // Point 0 seen by cameras 0-1 (spans the interval ending at 1), point 1
  // by 2-3 only (a static interval), point 2 by camera 1 alone.
  using window_test::Observation;
  const std::vector<BaObservation> obs{Observation(0, 0), Observation(1, 0), Observation(2, 1),
                                       Observation(3, 1), Observation(1, 2)};
  // 2 centres (6) - 1 zoom + 1 depth - 1 scale.
  EXPECT_EQ(DollyExtraParameters(zoom, dolly, obs), 5);
  EXPECT_EQ(DollyExtraParameters(zoom, zoom, obs), 0);  // nothing changes: no scale either
  EXPECT_EQ(DollyExtraParameters({}, {}, {}), 0);
}

TEST(DollyOrZoom, DepthReliefIsTheInverseDepthSpreadOverItsMedian) {
  std::vector<Eigen::Vector3d> flat, deep;
  for (int i = 0; i < 100; ++i) {
    flat.emplace_back(0, 0, 0.5);
    deep.emplace_back(0, 0, 0.05 + 0.01 * i);  // 0.05 .. 1.04
  }
  EXPECT_EQ(DepthRelief(flat), 0.0);
  EXPECT_NEAR(DepthRelief(deep), (0.95 - 0.15) / 0.55, 1e-12);
  EXPECT_EQ(DepthRelief({}), 0.0);
  // Every point at infinity: no median depth to compare with.
  EXPECT_EQ(DepthRelief({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0)}), 0.0);
  EXPECT_EQ(DepthRelief({Eigen::Vector3d(0, 0, NAN), Eigen::Vector3d(0, 0, 1)}), 0.0);  // NaN skipped
}

}  // namespace
}  // namespace hapcine
