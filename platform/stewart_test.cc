#include "platform/stewart.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rotation.h"
#include "platform/platform_config.h"

namespace hapcine {
namespace {

PlatformConfig Example() {
  return LoadPlatformFile(std::string(HAPCINE_SOURCE_DIR) + "/haptics/platform_stewart.json");
}

PlatformPose Pose(double x, double y, double z, double pitch_deg, double yaw_deg, double roll_deg) {
  PlatformPose p;
  p << x, y, z, DegToRad(pitch_deg), DegToRad(yaw_deg), DegToRad(roll_deg);
  return p;
}

TEST(Stewart, HeaveChangesEveryLegByTheKnownLength) {
  const StewartGeometry g = *Example().stewart;
  const LegLengths home = StewartLegLengths(g, PlatformPose::Zero());
  const LegLengths up = StewartLegLengths(g, Pose(0, 0.05, 0, 0, 0, 0));
  for (int i = 0; i < 6; ++i) {
    // A leg's horizontal reach stays; its height grows by 0.05 m.
    const Eigen::Vector3d d = g.top_m[i] - g.base_m[i];
    const double horizontal = std::hypot(d.x(), d.z());
    EXPECT_NEAR(home[i], std::hypot(horizontal, d.y()), 1e-12);
    EXPECT_NEAR(up[i], std::hypot(horizontal, d.y() + 0.05), 1e-12);
  }
}

TEST(Stewart, PitchLengthensTheFrontLegsAndShortensTheBackOnes) {
  const StewartGeometry g = *Example().stewart;
  const LegLengths home = StewartLegLengths(g, PlatformPose::Zero());
  const LegLengths pitched = StewartLegLengths(g, Pose(0, 0, 0, 5, 0, 0));
  for (int i = 0; i < 6; ++i) {
    // Front up: anchors at -Z rise.
    if (g.top_m[i].z() < -0.05) {
      EXPECT_GT(pitched[i], home[i]) << i;
    } else if (g.top_m[i].z() > 0.05) {
      EXPECT_LT(pitched[i], home[i]) << i;
    }
  }
}

TEST(Stewart, InverseThenForwardKinematicsReturnsThePose) {
  const StewartGeometry g = *Example().stewart;
  const PlatformPose poses[] = {Pose(0, 0, 0, 0, 0, 0),       Pose(0.05, 0, 0, 0, 0, 0),
                                Pose(0, -0.04, 0.03, 0, 0, 0), Pose(0, 0, 0, 8, 0, 0),
                                Pose(0, 0, 0, 0, -10, 0),      Pose(0, 0, 0, 0, 0, 7),
                                Pose(0.03, 0.02, -0.04, 4, 6, -5)};
  for (const PlatformPose& p : poses) {
    const auto back = StewartForwardKinematics(g, StewartLegLengths(g, p));
    ASSERT_TRUE(back.has_value()) << p.transpose();
    EXPECT_LT((*back - p).cwiseAbs().maxCoeff(), 1e-9) << p.transpose();
  }
}

TEST(Stewart, StrokeScaleBringsAnOutOfStrokePoseInside) {
  const StewartGeometry g = *Example().stewart;
  const PlatformPose far = Pose(0, 0.5, 0, 0, 0, 0);  // 0.5 m of heave: legs far out
  EXPECT_FALSE(LegsWithinStroke(g, StewartLegLengths(g, far)));
  const double s = StrokeScale(g, far, 0.01);
  EXPECT_GT(s, 0.0);
  EXPECT_LT(s, 1.0);
  EXPECT_TRUE(LegsWithinStroke(g, StewartLegLengths(g, s * far), 0.01));
  EXPECT_FALSE(LegsWithinStroke(g, StewartLegLengths(g, (s + 0.01) * far), 0.01));
  EXPECT_EQ(StrokeScale(g, Pose(0, 0.01, 0, 0, 0, 0), 0.01), 1.0);
}

}  // namespace
}  // namespace hapcine
