#include "extract/appearance_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "extract/feature_tracker.h"
#include "extract/test_frames.h"

namespace hapcine {
namespace {

using testing::AnalyticTexture;
using testing::MakeFrame;
using testing::NoiseTexture;
using testing::Shifted;

const cv::Size kDecoded(640, 480);

cv::Mat Gray(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

TEST(AppearanceCheckTest, PatchNccIsOneForTheSamePatchAndLowForAnother) {
  const cv::Mat gray = Gray(NoiseTexture(kDecoded, 3));
  cv::Mat a, b, c;
  ASSERT_TRUE(NormalizedPatch(gray, {100.25f, 200.5f}, 11, &a));
  ASSERT_TRUE(NormalizedPatch(gray, {100.25f, 200.5f}, 11, &b));
  ASSERT_TRUE(NormalizedPatch(gray, {300.f, 100.f}, 11, &c));
  EXPECT_NEAR(PatchNcc(a, b), 1.0, 1e-5);
  EXPECT_NEAR(PatchNcc(a, a), 1.0, 1e-5);
  EXPECT_LT(PatchNcc(a, c), 0.7);
}

// A flat patch has no appearance: it is not judged (scores 1), at birth or
// later.
TEST(AppearanceCheckTest, FlatPatchIsNotJudged) {
  cv::Mat flat(100, 100, CV_8UC1, cv::Scalar(90));
  cv::Mat patch;
  EXPECT_FALSE(NormalizedPatch(flat, {50.f, 50.f}, 11, &patch));
  EXPECT_TRUE(patch.empty());
  AppearanceCheck check;
  std::vector<float> ncc;
  check.Score(flat, {{50.f, 50.f}}, {7}, &ncc);  // born flat
  const cv::Mat textured = Gray(NoiseTexture({100, 100}, 5));
  check.Score(textured, {{50.f, 50.f}}, {7}, &ncc);
  ASSERT_EQ(ncc.size(), 1u);
  EXPECT_EQ(ncc[0], 1.0f);
  // Born textured, now flat (e.g. a fade): not judged either.
  check.Score(textured, {{30.f, 30.f}}, {8}, &ncc);
  check.Score(flat, {{30.f, 30.f}}, {8}, &ncc);
  EXPECT_EQ(ncc[0], 1.0f);
}

// Tracks on and beyond the image border get a finite score (the patch
// replicates the border), and tracks not passed are forgotten.
TEST(AppearanceCheckTest, BorderTracksAndForgetting) {
  const cv::Mat gray = Gray(NoiseTexture(kDecoded, 4));
  AppearanceCheck check;
  std::vector<float> ncc;
  const std::vector<cv::Point2f> at = {{0.f, 0.f}, {639.f, 479.f}, {-3.f, 200.f}};
  check.Score(gray, at, {1, 2, 3}, &ncc);
  EXPECT_EQ(check.size(), 3u);
  check.Score(gray, at, {1, 2, 3}, &ncc);
  for (float v : ncc) EXPECT_NEAR(v, 1.0, 1e-5);
  const cv::Mat moved = Gray(Shifted(NoiseTexture(kDecoded, 4), 2, 1, kDecoded, {0, 0}));
  check.Score(moved, at, {1, 2, 3}, &ncc);
  for (float v : ncc) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_LE(std::abs(v), 1.0f + 1e-5f);
  }
  check.Score(gray, {{10.f, 10.f}}, {1}, &ncc);
  EXPECT_EQ(check.size(), 1u);
}

// Frames of a textured square sliding over a background that moves the other
// way: corners on the square's silhouette mix both textures.
struct SlidingSquare {
  cv::Mat background = NoiseTexture({900, 700}, 11);
  cv::Mat square = NoiseTexture({900, 700}, 12);  // same colours: no dissolve suspected
  static constexpr int kSide = 200;
  // Top-left of the square in frame i, decoded pixels.
  static cv::Point2d Corner(int i) { return {200 + 2.0 * i, 140 + 1.0 * i}; }
  cv::Mat At(int i) const {
    cv::Mat out = Shifted(background, -2.0 * i, 0, kDecoded);
    const cv::Mat fg = Shifted(square, 2.0 * i, 1.0 * i, kDecoded);
    const cv::Point2d c = Corner(i);
    fg(cv::Rect(int(c.x), int(c.y), kSide, kSide)).copyTo(out(cv::Rect(int(c.x), int(c.y), kSide, kSide)));
    return out;
  }
};

// Distance of p (decoded px) inside the square's outline in frame i:
// negative outside.
double Inside(const SlidingSquare& s, int i, const Eigen::Vector2d& p) {
  const cv::Point2d c = SlidingSquare::Corner(i);
  const double dx = std::min(p.x() - c.x, c.x + SlidingSquare::kSide - 1 - p.x());
  const double dy = std::min(p.y() - c.y, c.y + SlidingSquare::kSide - 1 - p.y());
  return std::min(dx, dy);
}

struct Counts {
  int edge_born = 0, edge_alive = 0, interior_born = 0, interior_alive = 0;
};

Counts RunSquare(double min_ncc, int frames) {
  const SlidingSquare s;
  TrackerOptions o;
  o.max_tracks = 400;
  o.appearance_min_ncc = min_ncc;
  FeatureTracker tracker(o);
  std::map<long, int> born_as;  // 0 edge, 1 interior (frame-0 tracks only)
  FrameTracks t = tracker.Process(MakeFrame(s.At(0), 0));
  for (const TrackPoint& p : t.points) {
    const double d = Inside(s, 0, p.px);
    if (std::abs(d) <= 3) born_as[p.track_id] = 0;
    else if (d >= 12) born_as[p.track_id] = 1;
  }
  for (int i = 1; i < frames; ++i) t = tracker.Process(MakeFrame(s.At(i), i));
  Counts c;
  for (const auto& [id, kind] : born_as) (kind == 0 ? c.edge_born : c.interior_born)++;
  for (const TrackPoint& p : t.points) {
    auto it = born_as.find(p.track_id);
    if (it != born_as.end()) (it->second == 0 ? c.edge_alive : c.interior_alive)++;
  }
  return c;
}

TEST(AppearanceCheckTest, TrackerEndsSilhouetteCornersAndKeepsInteriorTracks) {
  const int frames = 16;
  const Counts off = RunSquare(0, frames), on = RunSquare(0.8, frames);
  ASSERT_GE(off.edge_born, 10);
  ASSERT_GE(off.interior_born, 30);
  // Without the check KLT keeps some silhouette corners sliding along the
  // edge; with it nearly all end.
  EXPECT_GE(off.edge_alive, 4);
  EXPECT_LE(on.edge_alive, off.edge_alive / 4);
  // Interior tracks are on one rigid (here: translating) surface.
  EXPECT_GE(on.interior_alive, 0.95 * off.interior_alive);
  EXPECT_GE(on.interior_alive, 0.9 * on.interior_born);
}

// A pure zoom by 1.5 % a frame (25 % over 16 frames): the patches change
// scale, and tracks on the rigid picture survive.
TEST(AppearanceCheckTest, TrackerKeepsTracksThroughAZoom) {
  auto run = [](double min_ncc) {
    TrackerOptions o;
    o.max_tracks = 300;
    o.appearance_min_ncc = min_ncc;
    FeatureTracker tracker(o);
    FrameTracks t;
    std::map<long, int> first;
    for (int i = 0; i < 16; ++i) {
      const double s = 1.0 / std::pow(1.015, i);  // texture_from_decoded scale
      const double cx = 319.5, cy = 239.5;
      const cv::Mat m = (cv::Mat_<double>(2, 3) << s, 0, cx - s * cx, 0, s, cy - s * cy);
      t = tracker.Process(MakeFrame(AnalyticTexture(kDecoded, m, 2), i));
      if (i == 0)
        for (const TrackPoint& p : t.points) first[p.track_id] = 1;
    }
    int alive = 0;
    for (const TrackPoint& p : t.points) alive += first.count(p.track_id);
    return alive;
  };
  const int off = run(0), on = run(0.8);
  ASSERT_GE(off, 100);
  EXPECT_GE(on, 0.95 * off);
}

TEST(AppearanceCheckTest, OptionIsChecked) {
  TrackerOptions o;
  o.appearance_min_ncc = 1;
  EXPECT_ANY_THROW(o.Check());
  o.appearance_min_ncc = -0.1;
  EXPECT_ANY_THROW(o.Check());
  o.appearance_min_ncc = 0.7;
  EXPECT_NO_THROW(o.Check());
}

}  // namespace
}  // namespace hapcine
