#include "estimate/window/loop_bundle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/rotation.h"

namespace hapcine {
namespace {

constexpr double kFocal = 0.6;
constexpr int kKeyframes = 40;  // 9 degrees apart: one turn
constexpr int kStretch = 6;     // keyframes a track lives (then a new id, as KLT)

// Keyframe k on a circle of radius 4 round the origin, looking at it
// (OpenCV axes: y down, turning about y).
BaCamera OrbitCamera(int k) {
  BaCamera c;
  const Eigen::AngleAxisd turn(k * 2 * kPi / kKeyframes, Eigen::Vector3d::UnitY());
  c.world_from_cam = Eigen::Quaterniond(turn);
  c.center = turn * Eigen::Vector3d(0, 0, -4);
  c.log_focal = std::log(kFocal);
  return c;
}

// The windows' solution: each keyframe turned a further 0.1 degree about
// x (about the first centre), the bend a window's tracks allow.
BaCamera Drifted(const BaCamera& c, int k) {
  const Eigen::Quaterniond d(Eigen::AngleAxisd(k * 0.1 * kPi / 180, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d c0 = OrbitCamera(0).center;
  BaCamera out = c;
  out.world_from_cam = d * c.world_from_cam;
  out.center = c0 + d * (c.center - c0);
  return out;
}

std::optional<Eigen::Vector2d> Sees(const BaCamera& c, const Eigen::Vector3d& x,
                                    const Eigen::Vector3d& normal) {
  if (normal.dot(c.center - x) <= 0) return std::nullopt;  // the far side of the ball
  const Eigen::Vector3d p = c.world_from_cam.conjugate() * (x - c.center);
  return Eigen::Vector2d(kFocal * p.x() / p.z(), kFocal * p.y() / p.z());
}

struct Orbit {
  std::vector<LoopKeyframe> keyframes;
  std::vector<BaCamera> truth;
};

// Points on a unit ball seen from the orbit. Each track lives kStretch
// keyframes, observed where the drifted cameras see its point (the windows'
// bias); with `revisit`, the last keyframes also observe, as the truth sees
// them, the points the first keyframes saw under their ids (the loop).
Orbit MakeOrbit(bool revisit) {
  Orbit o;
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 300; ++i) pts.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  for (int k = 0; k < kKeyframes; ++k) {
    o.truth.push_back(OrbitCamera(k));
    LoopKeyframe kf;
    kf.cam = Drifted(o.truth.back(), k);
    kf.first_window = k < 22 ? 0 : 1;
    kf.last_window = k < 20 ? 0 : 1;
    o.keyframes.push_back(kf);
  }
  for (size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < kKeyframes; ++k) {
      const long id = static_cast<long>(i) * 1000 + k / kStretch;
      if (const auto u = Sees(o.keyframes[k].cam, pts[i], pts[i])) o.keyframes[k].u[id] = *u;
      if (revisit && k >= kKeyframes - 4)
        if (const auto u = Sees(o.truth[k], pts[i], pts[i]); u && o.keyframes[0].u.count(i * 1000))
          o.keyframes[k].u[i * 1000] = *u;
    }
  return o;
}

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.conjugate() * b).angle() * 180 / kPi;
}

TEST(LoopBundleTest, TheLoopTakesOutTheWindowsDrift) {
  const Orbit o = MakeOrbit(true);
  EXPECT_GE(CountLoopTracks(o.keyframes), 40);
  const LoopBundleResult r = AdjustLoop(o.keyframes, {}, true, LoopBundleOptions{});
  ASSERT_TRUE(r.adjusted);
  const int last = kKeyframes - 1;
  const double before =
      AngleDeg(o.keyframes[last].cam.world_from_cam, o.truth[last].world_from_cam);
  const double after = AngleDeg(r.cameras[last].world_from_cam, o.truth[last].world_from_cam);
  EXPECT_NEAR(before, 3.9, 0.05);
  EXPECT_LT(after, before / 3);
  // The gauge: the first two keyframes as the windows left them.
  EXPECT_TRUE(r.cameras[1].center.isApprox(o.keyframes[1].cam.center, 1e-12));
  EXPECT_LT(AngleDeg(r.cameras[1].world_from_cam, o.keyframes[1].cam.world_from_cam), 1e-9);
}

// Degenerate: the same orbit without a revisit. Every track lives inside
// one window's stretch, so no loop is closed and nothing is adjusted.
TEST(LoopBundleTest, NoLoopNoAdjustment) {
  const Orbit o = MakeOrbit(false);
  EXPECT_EQ(CountLoopTracks(o.keyframes), 0);
  const LoopBundleResult r = AdjustLoop(o.keyframes, {}, true, LoopBundleOptions{});
  EXPECT_FALSE(r.adjusted);
  ASSERT_EQ(r.cameras.size(), o.keyframes.size());
  for (size_t k = 0; k < r.cameras.size(); ++k)
    EXPECT_EQ(r.cameras[k].center, o.keyframes[k].cam.center);
}

// Only a gap across windows that share no keyframe is a loop: a track seen
// on both sides of an overlap keyframe, or with a gap inside one window,
// was seen whole by a window.
TEST(LoopBundleTest, GapsInsideAWindowOrAcrossTheOverlapAreNoLoop) {
  std::vector<LoopKeyframe> kfs(6);
  for (int k = 0; k < 6; ++k) kfs[k].first_window = kfs[k].last_window = k < 3 ? 0 : 1;
  kfs[2].last_window = 1;  // the overlap keyframe
  const Eigen::Vector2d u(0.1, 0.1);
  kfs[0].u[1] = kfs[2].u[1] = u;  // gap inside window 0
  kfs[2].u[2] = kfs[4].u[2] = u;  // gap from the overlap keyframe into window 1
  kfs[0].u[3] = kfs[1].u[3] = kfs[2].u[3] = kfs[3].u[3] = u;  // contiguous across windows
  EXPECT_EQ(CountLoopTracks(kfs), 0);
  kfs[0].u[4] = kfs[5].u[4] = u;  // window 0 to window 1, unseen between
  EXPECT_EQ(CountLoopTracks(kfs), 1);
  const LoopBundleResult r = AdjustLoop(kfs, {}, true, LoopBundleOptions{});
  EXPECT_EQ(r.loop_tracks, 1);
  EXPECT_FALSE(r.adjusted);  // one loop track is below the minimum
}

}  // namespace
}  // namespace hapcine
