#include "estimate/window/jump_resection.h"

#include <gtest/gtest.h>

#include <random>

namespace hapcine {
namespace {

constexpr double kFocal = 0.9;  // normalised (focal / width)

BaCamera Camera(const Eigen::Vector3d& center, double pan_deg) {
  BaCamera c;
  c.center = center;
  c.world_from_cam = Eigen::AngleAxisd(pan_deg * M_PI / 180, Eigen::Vector3d::UnitY());
  c.log_focal = std::log(kFocal);
  return c;
}

// The tracks of `cam` on `points` (id = index) in front of it, with noise (normalised units).
KeyframeTracks See(const BaCamera& cam, const std::vector<Eigen::Vector3d>& points, double noise, std::mt19937* rng) {
  std::normal_distribution<double> n(0, noise);
  KeyframeTracks t;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d x = cam.world_from_cam.inverse() * (points[i] - cam.center);
    if (x.z() <= 0) continue;
    const Eigen::Vector2d u = kFocal * x.head<2>() / x.z();
    if (u.cwiseAbs().maxCoeff() > 0.5) continue;
    t[static_cast<long>(i)] = u + Eigen::Vector2d(n(*rng), n(*rng));
  }
  return t;
}

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.inverse() * b).angle() * 180 / M_PI;
}

struct Scene {
  std::vector<BaCamera> truth, chained;
  std::vector<KeyframeTracks> seen;
  std::vector<const KeyframeTracks*> tracks;
};

// A truck of four keyframes, then a jump back past the start with a 15
// degree pan; the chained (two-view) pose of the jump is 5 degrees and a
// step off, as a link of a few tracks leaves it.
Scene TruckThenJump(int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-3, 3), z(4, 15);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < points; ++i) pts.emplace_back(xy(rng), xy(rng), z(rng));
  Scene s;
  for (int i = 0; i < 4; ++i) s.truth.push_back(Camera({0.2 * i, 0, 0}, 0));
  s.truth.push_back(Camera({-0.3, 0.1, 0}, -15));
  s.chained = s.truth;
  s.chained[4] = Camera({0.9, 0, 0}, -10);
  for (const BaCamera& c : s.truth) s.seen.push_back(See(c, pts, 0.3 / 960, &rng));
  for (const auto& t : s.seen) s.tracks.push_back(&t);
  return s;
}

TEST(JumpResection, PlacesAJumpAgainstTheTruckTriangulatedPoints) {
  const Scene s = TruckThenJump(200, 1);
  const auto placed = ResectKeyframe(s.chained, s.tracks, 4);
  ASSERT_TRUE(placed.has_value());
  EXPECT_LT(AngleDeg(placed->world_from_cam, s.truth[4].world_from_cam), 0.2);
  EXPECT_LT((placed->center - s.truth[4].center).norm(), 0.03);
  EXPECT_EQ(placed->log_focal, s.chained[4].log_focal);
}

// Too few points that earlier keyframes triangulate: nothing to resect
// from, the two-view pose stays.
TEST(JumpResection, TooFewTriangulatedPointsGiveNothing) {
  const Scene s = TruckThenJump(200, 2);
  EXPECT_FALSE(ResectKeyframe(s.chained, s.tracks, 4, 100000).has_value());
  // The first keyframes triangulate nothing for keyframe 1: one view before it.
  EXPECT_FALSE(ResectKeyframe(s.chained, s.tracks, 1).has_value());
}

TEST(JumpResection, MoveChainFromMovesTheLaterKeyframesRigidly) {
  std::vector<BaCamera> cams = {Camera({0, 0, 0}, 0), Camera({1, 0, 0}, 5), Camera({2, 0, 1}, 20)};
  const BaCamera placed = Camera({0, 1, 0}, -30);
  const std::vector<BaCamera> before = cams;
  MoveChainFrom(1, placed, &cams);
  EXPECT_EQ(cams[0].center, before[0].center);
  EXPECT_LT((cams[1].center - placed.center).norm(), 1e-12);
  EXPECT_LT(AngleDeg(cams[1].world_from_cam, placed.world_from_cam), 1e-9);
  // The step from 1 to 2, seen from camera 1, is unchanged.
  const Eigen::Vector3d step_before = before[1].world_from_cam.inverse() * (before[2].center - before[1].center);
  const Eigen::Vector3d step_after = cams[1].world_from_cam.inverse() * (cams[2].center - cams[1].center);
  EXPECT_LT((step_before - step_after).norm(), 1e-12);
  EXPECT_LT(AngleDeg(before[1].world_from_cam.inverse() * before[2].world_from_cam,
                     cams[1].world_from_cam.inverse() * cams[2].world_from_cam),
            1e-9);
}

}  // namespace
}  // namespace hapcine
