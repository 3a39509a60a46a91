#include "estimate/stills_groups.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

#include "core/rotation.h"
#include "estimate/test_scene.h"
#include "estimate/track_estimator.h"

namespace hapcine {
namespace {

using testing::MakeFrameTracks;
using testing::SceneCamera;

// A still of `shot` seeing tracks first..first+n-1 (ids continue along a
// shot: consecutive views share tracks).
FrameTracks Still(int index, int shot, long first, int n = 20) {
  FrameTracks t;
  t.index = index;
  t.shot = shot;
  t.still = true;
  t.boundary = index == 0 ? ShotBoundary::kStart : ShotBoundary::kNone;
  for (long id = first; id < first + n; ++id) t.points.push_back({id, Eigen::Vector2d(id, id)});
  return t;
}

// Stills of shots of the given sizes, each split from the one before.
std::vector<FrameTracks> SplitStills(const std::vector<int>& shot_sizes) {
  std::vector<FrameTracks> frames;
  int index = 0;
  for (size_t s = 0; s < shot_sizes.size(); ++s)
    for (int k = 0; k < shot_sizes[s]; ++k, ++index) {
      frames.push_back(Still(index, static_cast<int>(s), 1000 * static_cast<long>(s) + 10 * k));
      if (k == 0 && index > 0) frames.back().boundary = ShotBoundary::kCut;
    }
  return frames;
}

std::vector<FrameTracks> Regrouped(std::vector<FrameTracks> frames, bool* regrouped = nullptr) {
  StillsRegrouper regrouper;
  EXPECT_TRUE(regrouper.Add(std::move(frames)).empty());  // stills are held to the end
  std::vector<FrameTracks> out = regrouper.Finish();
  if (regrouped) *regrouped = regrouper.regrouped();
  return out;
}

std::vector<int> Indices(const std::vector<FrameTracks>& frames) {
  std::vector<int> indices;
  for (const FrameTracks& t : frames) indices.push_back(t.index);
  return indices;
}

// A ring of 8 stills split after view 4 (view 5 links to nothing before
// it); view 7, back beside view 0, links to it (the loop): one group, the
// later shot first so that view 7 leads into view 0, all one shot.
TEST(StillsGroups, RingSplitIsMergedByItsLoopLink) {
  std::vector<FrameTracks> frames = SplitStills({5, 3});
  frames[7].earlier_shot_links.push_back({0, 0, 150});
  const std::vector<std::vector<int>> groups = StillsShotGroups(frames);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0], (std::vector<int>{1, 0}));
  bool regrouped = false;
  const std::vector<FrameTracks> out = Regrouped(frames, &regrouped);
  EXPECT_TRUE(regrouped);
  EXPECT_EQ(Indices(out), (std::vector<int>{5, 6, 7, 0, 1, 2, 3, 4}));
  for (size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].shot, 0) << k;
    EXPECT_EQ(out[k].boundary, k == 0 ? ShotBoundary::kStart : ShotBoundary::kNone) << k;
  }
}

// Two groups of stills that share nothing (no link across the split) stay
// two shots, in their order, untouched.
TEST(StillsGroups, UnrelatedStillGroupsStayApart) {
  const std::vector<FrameTracks> frames = SplitStills({4, 3});
  EXPECT_EQ(StillsShotGroups(frames).size(), 2u);
  bool regrouped = true;
  const std::vector<FrameTracks> out = Regrouped(frames, &regrouped);
  EXPECT_FALSE(regrouped);
  ASSERT_EQ(out.size(), frames.size());
  for (size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].index, frames[k].index);
    EXPECT_EQ(out[k].shot, frames[k].shot);
    EXPECT_EQ(out[k].boundary, frames[k].boundary);
  }
}

// Three shots, the third linked back to the first: those two are one shot,
// the middle one (linked to neither) stays a shot of its own after them.
TEST(StillsGroups, OnlyLinkedShotsAreMerged) {
  std::vector<FrameTracks> frames = SplitStills({3, 2, 3});
  frames[7].earlier_shot_links.push_back({0, 0, 80});
  const std::vector<FrameTracks> out = Regrouped(frames);
  EXPECT_EQ(Indices(out), (std::vector<int>{5, 6, 7, 0, 1, 2, 3, 4}));
  const std::vector<int> shots{0, 0, 0, 0, 0, 0, 1, 1};
  for (size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k].shot, shots[k]) << k;
  EXPECT_EQ(out[6].boundary, ShotBoundary::kCut);
}

// A later shot whose first view links to the earlier shot's last (the
// split was one view that linked to nothing): the earlier shot goes first.
TEST(StillsGroups, LinkAtTheSplitKeepsTheOrder) {
  std::vector<FrameTracks> frames = SplitStills({4, 3});
  frames[4].earlier_shot_links.push_back({0, 3, 40});
  EXPECT_EQ(StillsShotGroups(frames)[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(Indices(Regrouped(frames)), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
}

// The group's chain would start on a weak link (view 5 -> 6): view 5 is
// left out of it and follows as a shot of one view.
TEST(StillsGroups, WeakLeadInIsLeftOutOfTheChain) {
  std::vector<FrameTracks> frames = SplitStills({5, 3});
  frames[7].earlier_shot_links.push_back({0, 0, 150});
  frames[6].weak_link = true;
  const std::vector<FrameTracks> out = Regrouped(frames);
  EXPECT_EQ(Indices(out), (std::vector<int>{6, 7, 0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(out.back().shot, 1);
  EXPECT_EQ(out.back().boundary, ShotBoundary::kCut);
  for (size_t k = 0; k + 1 < out.size(); ++k) EXPECT_EQ(out[k].shot, 0) << k;
}

// Video is not stills: at the first frame after the first that is not a
// still, everything held is passed on in order, and so is every frame after.
TEST(StillsGroups, VideoPassesThroughInOrder) {
  StillsRegrouper regrouper;
  FrameTracks first = Still(0, 0, 0), second = Still(1, 0, 5), third = Still(2, 1, 900);
  first.still = second.still = third.still = false;
  third.earlier_shot_links.push_back({0, 0, 100});  // ignored: not stills
  EXPECT_TRUE(regrouper.Add(first).empty());
  EXPECT_EQ(Indices(regrouper.Add(second)), (std::vector<int>{0, 1}));
  EXPECT_EQ(Indices(regrouper.Add(third)), (std::vector<int>{2}));
  EXPECT_TRUE(regrouper.Finish().empty());
  EXPECT_FALSE(regrouper.regrouped());
}

// The path comes back in frame order, shots numbered by first appearance.
TEST(StillsGroups, RestoreFrameOrderSortsAndRenumbers) {
  CameraPath path;
  const std::vector<int> frame{5, 6, 0, 1, 2, 3};
  const std::vector<int> shot{0, 0, 0, 0, 1, 1};
  for (size_t k = 0; k < frame.size(); ++k) {
    CameraFrame f;
    f.frame = frame[k];
    f.time_s = frame[k] / 24.0;
    f.shot = shot[k];
    path.frames.push_back(f);
  }
  RestoreFrameOrder(&path);
  const std::vector<int> frames_after{0, 1, 2, 3, 5, 6}, shots_after{0, 0, 1, 1, 0, 0};
  for (size_t k = 0; k < path.frames.size(); ++k) {
    EXPECT_EQ(path.frames[k].frame, frames_after[k]);
    EXPECT_EQ(*path.frames[k].shot, shots_after[k]);
  }
}

// A panorama ring of 24 stills, 15 degrees apart (focal 800 px at 960 px
// width: 62 degrees of view), split after view 11 as where a view links to
// nothing: shot 1's tracks are new ids, but view 23, back beside view 0,
// continues view 0's tracks where view 22 had none (the tracker's link
// across the split). Regrouped, the estimator places the whole ring in one
// shot: view 12 turned 180 degrees from view 0, which no chain inside either
// half relates.
TEST(StillsGroups, RingOfStillsIsPlacedInOneShot) {
  constexpr int kW = 960, kH = 540;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), depth(4, 20);
  std::vector<Eigen::Vector3d> pts;  // around the camera, within 30 degrees of the horizon
  while (pts.size() < 4000) {
    const Eigen::Vector3d d(u(rng), 0.5 * u(rng), u(rng));
    if (d.norm() > 0.2) pts.push_back(depth(rng) * d.normalized());
  }
  auto cam_at = [](int i) {
    SceneCamera c;
    c.world_from_cam = Eigen::AngleAxisd(kPi / 12 * i, Eigen::Vector3d::UnitY());
    c.focal_px = 800;
    return c;
  };
  constexpr long kNewIds = 100000;  // shot 1's tracks: new ids
  std::vector<FrameTracks> frames;
  std::set<long> in_view0, in_view22;
  for (int i = 0; i < 24; ++i) {
    FrameTracks t = MakeFrameTracks(i, 25, cam_at(i), pts, kW, kH, 0.2, 0.0, &rng);
    t.still = true;
    t.shot = i < 12 ? 0 : 1;
    if (i == 12) t.boundary = ShotBoundary::kCut;
    for (TrackPoint& p : t.points) {
      if (i == 0) in_view0.insert(p.track_id);
      if (i == 22) in_view22.insert(p.track_id);
      const bool continued = i == 23 && in_view0.count(p.track_id) && !in_view22.count(p.track_id);
      if (i >= 12 && !continued) p.track_id += kNewIds;
    }
    if (i == 23) t.earlier_shot_links.push_back({0, 0, 200});
    frames.push_back(std::move(t));
  }
  StillsRegrouper regrouper;
  EXPECT_TRUE(regrouper.Add(frames).empty());
  TrackEstimatorOptions o;
  o.smooth = false;
  TrackCameraEstimator estimator(kW, kH, o);
  for (const FrameTracks& t : regrouper.Finish()) estimator.AddFrame(t);
  CameraPath path = estimator.Finish();
  ASSERT_TRUE(regrouper.regrouped());
  RestoreFrameOrder(&path);
  ASSERT_EQ(path.frames.size(), 24u);
  for (int i = 0; i < 24; ++i) {
    EXPECT_EQ(path.frames[i].frame, i);
    EXPECT_EQ(*path.frames[i].shot, 0) << i;
  }
  const Eigen::Quaterniond est_0_12 =
      Eigen::Quaterniond(path.frames[0].world_from_cam).conjugate() * Eigen::Quaterniond(path.frames[12].world_from_cam);
  const Eigen::Quaterniond true_0_12 = cam_at(0).world_from_cam.conjugate() * cam_at(12).world_from_cam;
  EXPECT_LT(AngleBetweenDeg(est_0_12, true_0_12), 0.5);
  EXPECT_NEAR(*path.frames[12].focal_px / 800, 1.0, 0.02);
}

}  // namespace
}  // namespace hapcine
