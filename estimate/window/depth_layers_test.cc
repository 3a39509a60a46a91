#include "estimate/window/depth_layers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

// A grid of samples 0.01 apart over [-0.2, 0.2]^2, inverse depth from `w_of`.
template <typename F>
std::vector<DepthSample> Grid(F w_of, long first_id = 0) {
  std::vector<DepthSample> out;
  long id = first_id;
  for (int y = -20; y <= 20; ++y)
    for (int x = -20; x <= 20; ++x) {
      const Eigen::Vector2d u(0.01 * x, 0.01 * y);
      out.push_back({id++, u, w_of(u)});
    }
  return out;
}

// Foreground (w = 1) left of x = 0, background (w = 0.2) right of it.
double TwoLayers(const Eigen::Vector2d& u) { return u.x() < 0 ? 1.0 : 0.2; }

TEST(DepthLayers, TrackBetweenTwoLayersIsFlagged) {
  auto frame = Grid(TwoLayers);
  frame.push_back({-1, Eigen::Vector2d(0.005, 0.003), 0.6});  // a corner on the silhouette, in between
  const std::vector<int> v = JudgeDepthLayers(frame);
  EXPECT_EQ(v.back(), 1);
  // The rigid points next to the edge belong to a layer: judged, not flagged.
  int judged = 0;
  for (size_t i = 0; i + 1 < frame.size(); ++i) {
    EXPECT_NE(v[i], 1) << i;
    judged += v[i] == 0;
  }
  EXPECT_GT(judged, 0);
}

TEST(DepthLayers, SlantedSurfaceFlagsNothing) {
  // A floor: inverse depth changes linearly down the image, no depth edge,
  // large spread in every neighbourhood relative to the frame's.
  const auto frame = Grid([](const Eigen::Vector2d& u) { return 0.5 + 2.0 * u.y(); });
  for (int x : JudgeDepthLayers(frame)) EXPECT_NE(x, 1);
}

TEST(DepthLayers, InvariantToAffineInverseDepth) {
  // The mirrored or rescaled reconstruction (w' = a + b w) gives the same verdicts.
  auto frame = Grid(TwoLayers);
  frame.push_back({-1, Eigen::Vector2d(0.005, 0.003), 0.6});
  auto moved = frame;
  for (auto& s : moved) s.w = 3.0 - 2.5 * s.w;
  EXPECT_EQ(JudgeDepthLayers(frame), JudgeDepthLayers(moved));
}

TEST(DepthLayers, DegenerateInputs) {
  EXPECT_TRUE(JudgeDepthLayers({}).empty());
  // All at one depth: no spread, nothing judged.
  for (int x : JudgeDepthLayers(Grid([](const Eigen::Vector2d&) { return 0.3; }))) EXPECT_EQ(x, -1);
  // Isolated samples (no neighbours within the radius): not judged.
  std::vector<DepthSample> sparse = {{1, {0, 0}, 1}, {2, {0.3, 0}, 0.1}, {3, {-0.3, 0}, 0.5}};
  for (int x : JudgeDepthLayers(sparse)) EXPECT_EQ(x, -1);
  EXPECT_TRUE(TracksBetweenDepthLayers(std::vector<std::vector<DepthSample>>{}).empty());
}

TEST(DepthLayers, MajorityOverReferenceFrames) {
  auto flagged = Grid(TwoLayers);
  flagged.push_back({-1, Eigen::Vector2d(0.005, 0.003), 0.6});
  auto rigid = Grid(TwoLayers);
  rigid.push_back({-1, Eigen::Vector2d(0.005, 0.003), 0.2});  // with the background here
  EXPECT_EQ(TracksBetweenDepthLayers({flagged, flagged, rigid}), std::set<long>{-1});
  EXPECT_TRUE(TracksBetweenDepthLayers({flagged, rigid, rigid}).empty());
}

TEST(DepthLayers, FromCamerasTriangulatesInEachKeyframe) {
  // Two cameras translating sideways; a foreground plane at z = 2 (x < 0) and
  // a background plane at z = 10 (x > 0), and one "track" whose second
  // observation matches a point at z = 4 on the edge: between the layers.
  std::vector<BaCamera> cams(2);
  cams[1].center = Eigen::Vector3d(0.2, 0, 0);
  std::map<long, KeyframeTrack> tracks;
  long id = 0;
  auto add = [&](const Eigen::Vector3d& X, long track) {
    KeyframeTrack t;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d p = X - cams[k].center;
      t.push_back({k, Eigen::Vector2d(p.x() / p.z(), p.y() / p.z())});
    }
    tracks[track] = t;
  };
  for (int y = -10; y <= 10; ++y)
    for (int x = -10; x <= 10; ++x) {
      const double ux = 0.01 * x, uy = 0.01 * y, z = ux < 0 ? 2.0 : 10.0;
      add(Eigen::Vector3d(ux * z, uy * z, z), id++);
    }
  add(Eigen::Vector3d(0.002 * 4, 0.003 * 4, 4.0), -1);
  EXPECT_EQ(TracksBetweenDepthLayers(cams, tracks), std::set<long>{-1});
}

}  // namespace
}  // namespace hapcine
