#include "estimate/axial_ambiguity.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace hapcine
