#include "estimate/window/window_points.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

// OpenCV axes: camera looking along +z, u = (x / z, y / z) at focal 1 (log 0).
Eigen::Vector2d Project(const BaCamera& cam, const Eigen::Vector3d& X) {
  const Eigen::Vector3d p = cam.world_from_cam.conjugate() * (X - cam.center);
  return p.head<2>() / p.z();
}

TEST(SelectWindowPoints, KeepsTracksSeenTwiceAndNotOutliersLongestFirst) {
  const KeyframeTracks k0 = {{1, {0.0, 0.0}}, {2, {0.1, 0.0}}, {3, {0.2, 0.0}}, {4, {0.3, 0.0}}};
  const KeyframeTracks k1 = {{1, {0.0, 0.1}}, {2, {0.1, 0.1}}, {4, {0.3, 0.1}}, {5, {0.4, 0.1}}};
  const KeyframeTracks k2 = {{1, {0.0, 0.2}}, {4, {0.3, 0.2}}};
  const WindowTracks w = SelectWindowPoints({&k0, &k1, &k2}, {4}, 10, 0);
  // 3 and 5 are seen once, 4 is an outlier: 1 (three keyframes) and 2 (two).
  ASSERT_EQ(w.order.size(), 2u);
  EXPECT_EQ(w.order[0], std::make_pair(-3, 1L));
  EXPECT_EQ(w.order[1], std::make_pair(-2, 2L));
  EXPECT_EQ(w.point_of_track.at(1), 0);
  EXPECT_EQ(w.point_of_track.at(2), 1);
  EXPECT_EQ(w.seen.at(1), (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(SelectWindowPoints({&k0, &k1, &k2}, {}, 1, 0).order.size() == 1u);  // the budget
}

TEST(InitWindowPoints, TriangulatesFromTheWidestBaselineOrFallsBack) {
  std::vector<BaCamera> cams(3);
  cams[1].center = Eigen::Vector3d(0.1, 0, 0);
  cams[2].center = Eigen::Vector3d(0.5, 0, 0);
  const Eigen::Vector3d X(0.2, -0.1, 4.0);
  KeyframeTracks k0 = {{7, Project(cams[0], X)}}, k1 = {{7, Project(cams[1], X)}},
                 k2 = {{7, Project(cams[2], X)}};
  const std::vector<const KeyframeTracks*> at = {&k0, &k1, &k2};
  const WindowTracks w = SelectWindowPoints(at, {}, 10, 0);
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
  InitWindowPoints(cams, w, at, true, 0.01, &points, &obs);
  ASSERT_EQ(points.size(), 1u);
  ASSERT_EQ(obs.size(), 3u);  // one per keyframe that sees it
  const BaPoint& p = points[0];
  EXPECT_EQ(p.anchor, cams[0].center);
  // X = anchor + d / rho: the exact point from noise-free rays.
  const Eigen::Vector3d back = p.anchor + p.homogeneous.head<3>() / p.homogeneous(3);
  EXPECT_NEAR((back - X).norm(), 0.0, 1e-9);
  // Without depth: a bearing (rho = 0) along the same ray.
  InitWindowPoints(cams, w, at, false, 0.01, &points, &obs);
  EXPECT_EQ(points[0].homogeneous(3), 0.0);
  EXPECT_NEAR(points[0].homogeneous.head<3>().normalized().dot(X.normalized()), 1.0, 1e-12);
  // No baseline at all: the fallback inverse depth, finite.
  std::vector<BaCamera> still(3);
  InitWindowPoints(still, w, at, true, 0.01, &points, &obs);
  const Eigen::Vector4d h = points[0].homogeneous;
  EXPECT_NEAR(h(3) / h.head<3>().norm(), 0.01, 1e-12);
  EXPECT_TRUE(h.allFinite());
}

}  // namespace
}  // namespace hapcine
