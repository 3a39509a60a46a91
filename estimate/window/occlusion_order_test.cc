#include "estimate/window/occlusion_order.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

// A camera dollying forward along +z at constant focal towards a background
// plane (z = 10) with a square subject in front of it (z = 3, |x|, |y| < 0.4):
// the subject grows faster than the background and covers it at its edges.
// Normalised image coordinates (fraction of the width), half extent 0.5 x 0.28.
constexpr double kFocal = 1.0, kBackground = 10, kSubject = 3, kHalf = 0.4;
constexpr int kFrames = 26, kKeyframeEvery = 5;
const Eigen::Vector2d kHalfExtent(0.5, 0.28);

struct Scene {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::map<long, Eigen::Vector2d>> frames;
  std::vector<int> frame_keyframe;
  std::map<long, KeyframeTrack> tracks;  // observations at keyframes
  std::vector<BaCamera> cams;            // the true keyframe cameras
};

Scene MakeScene(bool with_subject) {
  Scene s;
  for (double x = -5; x <= 5; x += 0.25)
    for (double y = -2.8; y <= 2.8; y += 0.25) s.points.push_back({x, y, kBackground});
  if (with_subject)
    for (double x = -kHalf + 0.05; x < kHalf; x += 0.1)
      for (double y = -kHalf + 0.05; y < kHalf; y += 0.1) s.points.push_back({x, y, kSubject});
  for (int f = 0; f < kFrames; ++f) {
    const double t = 1.0 * f / (kFrames - 1);  // camera centre (0, 0, t)
    const double edge = kFocal * kHalf / (kSubject - t);  // the subject's half size in the image
    std::map<long, Eigen::Vector2d> frame;
    for (size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d& p = s.points[i];
      const Eigen::Vector2d u = kFocal * p.head<2>() / (p.z() - t);
      if (std::abs(u.x()) > kHalfExtent.x() || std::abs(u.y()) > kHalfExtent.y()) continue;
      if (with_subject && p.z() > kSubject && std::abs(u.x()) < edge && std::abs(u.y()) < edge) continue;
      frame[static_cast<long>(i)] = u;
    }
    s.frames.push_back(frame);
    s.frame_keyframe.push_back(f / kKeyframeEvery);
    if (f % kKeyframeEvery == 0) {
      BaCamera c;
      c.center = Eigen::Vector3d(0, 0, t);
      c.log_focal = std::log(kFocal);
      s.cams.push_back(c);
      for (const auto& [id, u] : frame) s.tracks[id].push_back({f / kKeyframeEvery, u});
    }
  }
  return s;
}

std::vector<const std::map<long, Eigen::Vector2d>*> Pointers(const Scene& s) {
  std::vector<const std::map<long, Eigen::Vector2d>*> out;
  for (const auto& f : s.frames) out.push_back(&f);
  return out;
}

// The other branch of the axial ambiguity (axial_ambiguity.h), exactly: each
// image point scales by 1/s = a - b w (a = f0 / f, b = t f0 / f); with the
// inverse depths re-arranged as w' = alpha + beta w, beta < 0, the cameras
// b' = b / beta, a' = a + b alpha / beta explain the same tracks.
constexpr double kAlpha = 0.45, kBeta = -1;
std::vector<BaCamera> MirroredCameras(const std::vector<BaCamera>& cams) {
  std::vector<BaCamera> out = cams;
  for (auto& c : out) {
    const double a = kFocal / std::exp(c.log_focal), b = c.center.z() * a;
    const double a2 = a + b * kAlpha / kBeta, b2 = b / kBeta;
    c.log_focal = std::log(kFocal / a2);
    c.center = Eigen::Vector3d(0, 0, b2 / a2);
  }
  return out;
}

TEST(OcclusionOrder, SilhouetteEventsAreFoundAwayFromTheBorder) {
  const Scene s = MakeScene(true);
  const auto events = FindOcclusionEvents(Pointers(s), s.frame_keyframe, kHalfExtent);
  ASSERT_GT(events.size(), 20u);
  for (const auto& e : events) {
    // Every event is a background point next to the subject's outline.
    EXPECT_EQ(s.points[e.track].z(), kBackground);
    const Eigen::Vector2d u = s.tracks.count(e.track) ? s.tracks.at(e.track).front().second : Eigen::Vector2d::Zero();
    EXPECT_LT(std::abs(u.x()), kHalfExtent.x() - 0.04);
    EXPECT_GE(e.neighbours.size(), 3u);
  }
}

TEST(OcclusionOrder, TrueBranchAgreesAndMirroredBranchDisagrees) {
  const Scene s = MakeScene(true);
  const auto events = FindOcclusionEvents(Pointers(s), s.frame_keyframe, kHalfExtent);
  const OcclusionVotes truth = CountOcclusionVotes(s.cams, s.tracks, events);
  EXPECT_GT(truth.agree, 10);
  EXPECT_EQ(truth.disagree, 0);
  EXPECT_GT(truth.Z(), 3);
  const std::vector<BaCamera> mirrored = MirroredCameras(s.cams);
  // The mirrored cameras explain the same tracks with w' = alpha + beta w.
  const Eigen::Vector3d& subject = s.points.back();
  EXPECT_NEAR(TrackInverseDepth(mirrored, s.tracks.at(static_cast<long>(s.points.size() - 1)), 0),
              kAlpha + kBeta / subject.z(), 1e-6);
  EXPECT_GT(mirrored.back().log_focal, mirrored.front().log_focal);  // a zoom in ...
  EXPECT_LT(mirrored.back().center.z(), 0);                          // ... moving backward
  const OcclusionVotes mirror = CountOcclusionVotes(mirrored, s.tracks, events);
  EXPECT_EQ(mirror.agree, truth.disagree);
  EXPECT_EQ(mirror.disagree, truth.agree);
  const auto out = ContradictedByOcclusion({truth, mirror});
  EXPECT_EQ(out, (std::vector<char>{0, 1}));
  EXPECT_EQ(ContradictedByOcclusion({mirror, truth}), (std::vector<char>{1, 0}));
}

TEST(OcclusionOrder, NoOccluderGivesNoEvidence) {
  const Scene s = MakeScene(false);
  // Tracks end only at the image border (the dolly pushes them out).
  EXPECT_TRUE(FindOcclusionEvents(Pointers(s), s.frame_keyframe, kHalfExtent).empty());
  const OcclusionVotes v = CountOcclusionVotes(s.cams, s.tracks, {});
  EXPECT_EQ(v.agree + v.disagree, 0);
  EXPECT_EQ(v.Z(), 0);
  EXPECT_EQ(ContradictedByOcclusion({v, v}), (std::vector<char>{0, 0}));
}

TEST(OcclusionOrder, OnlyContradictionsRuleNothingOut) {
  // Every candidate contradicted: no branch is supported, so no evidence to
  // choose by (the fit decides); weak votes neither.
  OcclusionVotes bad, weak;
  bad.disagree = 20;
  weak.agree = 2;
  EXPECT_EQ(ContradictedByOcclusion({bad, bad}), (std::vector<char>{0, 0}));
  EXPECT_EQ(ContradictedByOcclusion({weak, bad}), (std::vector<char>{0, 0}));
  EXPECT_TRUE(ContradictedByOcclusion({}).empty());
  OcclusionVotes good;
  good.agree = 9;
  good.disagree = 1;
  EXPECT_EQ(ContradictedByOcclusion({good, bad, weak}), (std::vector<char>{0, 1, 0}));
}

TEST(OcclusionOrder, DegenerateInputIsNanFree) {
  Scene s = MakeScene(true);
  const auto events = FindOcclusionEvents(Pointers(s), s.frame_keyframe, kHalfExtent);
  // No translation: nothing can be triangulated, no votes.
  std::vector<BaCamera> still = s.cams;
  for (auto& c : still) c.center.setZero();
  const OcclusionVotes v = CountOcclusionVotes(still, s.tracks, events);
  EXPECT_EQ(v.agree + v.disagree, 0);
  EXPECT_TRUE(std::isfinite(v.Z()));
  // One observation, a reference out of range, no tracks at all.
  EXPECT_TRUE(std::isnan(TrackInverseDepth(s.cams, {{0, Eigen::Vector2d(0.1, 0)}}, 0)));
  EXPECT_TRUE(std::isnan(TrackInverseDepth(s.cams, s.tracks.begin()->second, 99)));
  const OcclusionVotes none = CountOcclusionVotes(s.cams, {}, events);
  EXPECT_EQ(none.agree + none.disagree, 0);
  // Empty frames (a blank) end no track; empty input finds nothing.
  std::map<long, Eigen::Vector2d> empty;
  std::vector<const std::map<long, Eigen::Vector2d>*> frames{&s.frames[0], &empty, &s.frames[0]};
  EXPECT_TRUE(FindOcclusionEvents(frames, {0, 0, 0}, kHalfExtent).empty());
  EXPECT_TRUE(FindOcclusionEvents({}, {}, kHalfExtent).empty());
}

}  // namespace
}  // namespace hapcine
