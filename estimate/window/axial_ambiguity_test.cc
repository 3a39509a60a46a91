#include "estimate/window/axial_ambiguity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hapcine {
namespace {

using Match = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

TEST(AxialAmbiguity, AxialMotionIsAlongTheOpticalAxis) {
  std::vector<BaCamera> cams(3);
  cams[1].center = Eigen::Vector3d(0.01, 0, 0.5);
  cams[2].center = Eigen::Vector3d(0.02, 0, 1.0);
  EXPECT_TRUE(IsAxialMotion(cams, 0));
  cams[2].center = Eigen::Vector3d(1.0, 0, 0.2);  // sideways: a traveling shot
  EXPECT_FALSE(IsAxialMotion(cams, 0));
  cams[1].center = cams[2].center = Eigen::Vector3d::Zero();  // no motion at all
  EXPECT_FALSE(IsAxialMotion(cams, 0));
  EXPECT_FALSE(IsAxialMotion(cams, 2));  // nothing after the pivot
}

TEST(AxialAmbiguity, AxialDirectionIsTheSignOfTheFarthestMoveInThePivotCamera) {
  std::vector<BaCamera> cams(3);
  cams[1].center = Eigen::Vector3d(0, 0, 0.3);
  cams[2].center = Eigen::Vector3d(0, 0, -1.0);  // farthest: backward
  EXPECT_EQ(AxialDirection(cams, 0), -1);
  EXPECT_EQ(AxialDirection(cams, 1), -1);  // from the second camera, too
  // The pivot turned half a turn about y: its forward is the world's -z.
  cams[0].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  EXPECT_EQ(AxialDirection(cams, 0), 1);
  cams[1].center = cams[2].center = Eigen::Vector3d::Zero();
  EXPECT_EQ(AxialDirection(cams, 0), 0);  // no move
  EXPECT_EQ(AxialDirection(cams, 2), 0);  // nothing after the pivot
  EXPECT_EQ(AxialDirection(cams, -1), 0);
}

// debug_moves: a cue that supports the per-keyframe-focal solve had ruled
// out the constant-focal solve moving the same way; the window's BIC must
// decide between those two (the constant focal fitted better: a zoom was
// invented on a fixed lens).
TEST(AxialAmbiguity, ABranchCueRulesOutOnlyTheOtherBranch) {
  // [0] constant focal, backward; [1] per-keyframe focal, backward (the
  // cue's best); [2] mirrored branch, forward.
  const std::vector<int> direction{-1, -1, 1};
  EXPECT_EQ(RuledOutOtherBranch({1, 0, 1}, direction, {0, 71, 0}), (std::vector<char>{0, 0, 1}));
  // The cue supports the forward branch: both backward solves stay out.
  EXPECT_EQ(RuledOutOtherBranch({1, 1, 0}, direction, {0, 3, 60}), (std::vector<char>{1, 1, 0}));
  // Occlusion z-scores may be negative: the best kept candidate decides.
  EXPECT_EQ(RuledOutOtherBranch({1, 0, 0}, direction, {-2.5, 0.5, 2.2}), (std::vector<char>{1, 0, 0}));
  EXPECT_EQ(RuledOutOtherBranch({0, 1, 1}, direction, {2.5, -2.1, -3.0}), (std::vector<char>{0, 0, 1}));
  // No evidence, or everything out: the verdict is kept.
  EXPECT_EQ(RuledOutOtherBranch({0, 0, 0}, direction, {0, 0, 0}), (std::vector<char>{0, 0, 0}));
  EXPECT_EQ(RuledOutOtherBranch({1, 1, 1}, direction, {1, 2, 3}), (std::vector<char>{1, 1, 1}));
  // The best kept candidate does not move: no branch to keep.
  EXPECT_EQ(RuledOutOtherBranch({1, 0}, {-1, 0}, {0, 30}), (std::vector<char>{1, 0}));
  // Mismatched sizes: only the common prefix is judged, the rest kept.
  EXPECT_EQ(RuledOutOtherBranch({1, 0, 1}, {-1, -1}, {0, 5}), (std::vector<char>{0, 0, 1}));
}

TEST(AxialAmbiguity, RadialScalePercentileSkipsTheCentre) {
  std::vector<Match> m;
  for (int i = 1; i <= 10; ++i) {
    const Eigen::Vector2d u(0.2, 0.05 * i);
    m.push_back({u, u * (1 + 0.01 * i)});
  }
  m.push_back({Eigen::Vector2d(0.001, 0), Eigen::Vector2d(0.5, 0)});  // near the centre: ignored
  EXPECT_NEAR(RadialScalePercentile(m, 0.0), 1.01, 1e-12);
  EXPECT_NEAR(RadialScalePercentile(m, 1.0), 1.10, 1e-12);
  EXPECT_EQ(RadialScalePercentile({}, 0.5), 1.0);
}

TEST(AxialAmbiguity, MirroredBranchFlipsTheMoveAndZoomsFromTheFarPoints) {
  // Backward move at constant focal (the wrong branch of a dolly zoom).
  std::vector<BaCamera> cams(2);
  cams[1].center = Eigen::Vector3d(0, 0, -1);
  // Subject keeps its size (scale 1), background shrinks to 0.6 .. 0.9.
  std::vector<std::vector<Match>> matches(2);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d u(0.3, 0.01 * i);
    matches[1].push_back({u, u * (i < 10 ? 1.0 : 0.6 + 0.03 * (i - 10))});
  }
  const auto out = MirroredAxialBranch(cams, 0, matches);
  EXPECT_GT(out[1].center.z(), 0.99);  // now forward
  // Forward: the far points (the least growing) define the zoom.
  // 10th percentile of the 20 scales (the third smallest): 0.66.
  EXPECT_NEAR(std::exp(out[1].log_focal - out[0].log_focal), 0.66, 1e-9);
  EXPECT_EQ(out[0].center, Eigen::Vector3d::Zero());
}

// A forward dolly with a zoom out, a level camera 1.5 units above a floor
// (OpenCV axes: y down), a subject and a back wall; the observations exact.
struct AxialScene {
  std::vector<BaCamera> cams;
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
};

BaPoint PointAt(const Eigen::Vector3d& x) {
  BaPoint p;
  p.anchor = Eigen::Vector3d::Zero();
  p.homogeneous << x, 1;
  p.homogeneous.normalize();
  return p;
}

AxialScene DollyZoomOverAFloor() {
  AxialScene s;
  s.cams.resize(5);
  s.cams[0].fixed = true;
  for (int k = 1; k < 5; ++k) {
    s.cams[k].center = Eigen::Vector3d(0, 0, 0.8 * k);
    s.cams[k].log_focal = std::log((7 - 0.8 * k) / 7);  // the subject 7 units ahead keeps its size
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 60; ++i) {
    const double z = 9 + 6 * (u(rng) + 1);  // floor from 9 to 21 ahead
    s.points.push_back(PointAt(Eigen::Vector3d(0.3 * z * u(rng), 1.5, z)));
    s.points.push_back(PointAt(Eigen::Vector3d(0.4 * u(rng), 0.6 * u(rng), 7)));             // subject
    s.points.push_back(PointAt(Eigen::Vector3d(6 * u(rng), -3 + 4 * (u(rng) + 1) / 2, 25)));  // wall
  }
  for (size_t k = 0; k < s.cams.size(); ++k)
    for (size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d x = s.points[i].Direction() / s.points[i].homogeneous(3) - s.cams[k].center;
      s.obs.push_back({static_cast<int>(k), static_cast<int>(i), std::exp(s.cams[k].log_focal) * x.head<2>() / x.z()});
    }
  return s;
}

double MaxError(const AxialScene& s) {
  double m = 0;
  for (double e : ObservationErrors(s.cams, s.points, s.obs, true)) m = std::max(m, e);
  return m;
}

TEST(AxialAmbiguity, ShiftKeepsEveryTrackOfAMoveAlongTheAxis) {
  AxialScene s = DollyZoomOverAFloor();
  ASSERT_LT(MaxError(s), 1e-12);
  for (double delta : {-0.03, 0.05, 0.5}) {
    AxialScene t = s;
    const auto cams = ShiftedAxialSolution(s.cams, 0, delta);
    ASSERT_TRUE(cams);
    t.cams = *cams;
    t.points = ShiftedAxialPoints(s.cams[0], delta, s.points);
    EXPECT_LT(MaxError(t), 1e-12) << delta;
    // Every inverse depth in the pivot moved by delta; the zoom with the move.
    const auto before = InverseDepthsIn(s.cams[0], s.points, {});
    const auto after = InverseDepthsIn(t.cams[0], t.points, {});
    ASSERT_EQ(before.size(), after.size());
    for (size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(after[i].z(), before[i].z() + delta, 1e-12);
    EXPECT_NEAR(t.cams[4].log_focal, s.cams[4].log_focal - std::log(1 + delta * 3.2), 1e-12);
  }
}

TEST(AxialAmbiguity, ShiftRefusesCamerasPastTheVanishingPlane) {
  const AxialScene s = DollyZoomOverAFloor();
  EXPECT_FALSE(ShiftedAxialSolution(s.cams, 0, -1 / 3.2));  // the last camera on Z = -1/delta
  EXPECT_FALSE(ShiftedAxialSolution(s.cams, 0, std::nan("")));
  EXPECT_FALSE(ShiftedAxialSolution(s.cams, 7, 0.1));
  std::vector<BaCamera> held = s.cams;
  held[1].fixed = true;  // a held camera away from the pivot pins the depths
  EXPECT_FALSE(ShiftedAxialSolution(held, 0, 0.1));
}

TEST(AxialAmbiguity, ShiftForMotionPlanePutsTheFloorParallelToTheMove) {
  const AxialScene truth = DollyZoomOverAFloor();
  // The fit's start: the farthest points (the wall, 1/25) put at infinity.
  AxialScene s = truth;
  s.cams = *ShiftedAxialSolution(truth.cams, 0, -1.0 / 25);
  s.points = ShiftedAxialPoints(truth.cams[0], -1.0 / 25, truth.points);
  const auto shift = ShiftForMotionPlane(s.cams, 0, InverseDepthsIn(s.cams[0], s.points, {}));
  ASSERT_TRUE(shift);
  EXPECT_NEAR(shift->delta, 1.0 / 25, 1e-9);
  EXPECT_NEAR(shift->plane.y(), 1 / 1.5, 1e-9);  // the floor: w = y / 1.5 - 1/25
  EXPECT_EQ(shift->inliers, 60);
  EXPECT_NEAR(shift->min_w, 0, 1e-12);
  // Not along the axis: no shift.
  std::vector<BaCamera> sideways = s.cams;
  for (size_t k = 1; k < sideways.size(); ++k) sideways[k].center = Eigen::Vector3d(0.8 * k, 0, 0);
  EXPECT_FALSE(ShiftForMotionPlane(sideways, 0, InverseDepthsIn(s.cams[0], s.points, {})));
}

TEST(AxialAmbiguity, ShiftForMotionPlaneRefusesAPlaneBeyondInfinity) {
  // A floor that would need the wall beyond infinity: it is not parallel to the move.
  AxialScene s = DollyZoomOverAFloor();
  auto xyw = InverseDepthsIn(s.cams[0], s.points, {});
  for (auto& p : xyw)
    if (std::abs(p.z() - p.y() / 1.5) < 1e-9) p.z() += 0.2;  // floor: w = y / 1.5 + 0.2
  EXPECT_FALSE(ShiftForMotionPlane(s.cams, 0, xyw));
}

}  // namespace
}  // namespace hapcine
