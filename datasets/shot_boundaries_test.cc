#include "datasets/shot_boundaries.h"

#include <gtest/gtest.h>

namespace hapcine {
namespace {

// Frames 0..n-1 with shots starting at the given frames.
std::vector<ShotSample> Samples(int n, std::vector<int> gt_starts, std::vector<int> est_starts) {
  std::vector<ShotSample> v;
  for (int f = 0; f < n; ++f) {
    ShotSample s;
    s.frame = f;
    for (int b : gt_starts) s.gt_shot += f >= b;
    for (int b : est_starts) s.est_shot += f >= b;
    v.push_back(s);
  }
  return v;
}

TEST(ShotBoundaries, ExactCutIsFound) {
  const ShotBoundaryScore s = ScoreShotBoundaries(Samples(100, {40}, {40}), 2);
  EXPECT_EQ(s.gt_boundaries, std::vector<int>({40}));
  EXPECT_EQ(s.est_boundaries, std::vector<int>({40}));
  EXPECT_EQ(s.matched, 1);
  EXPECT_DOUBLE_EQ(*s.precision, 1);
  EXPECT_DOUBLE_EQ(*s.recall, 1);
}

TEST(ShotBoundaries, MissedCutAndExtraSplit) {
  // One shot found for two; elsewhere a split that is not in the truth.
  ShotBoundaryScore s = ScoreShotBoundaries(Samples(100, {40}, {}), 2);
  EXPECT_EQ(s.matched, 0);
  EXPECT_FALSE(s.precision.has_value());
  EXPECT_DOUBLE_EQ(*s.recall, 0);
  s = ScoreShotBoundaries(Samples(100, {}, {70}), 2);
  EXPECT_DOUBLE_EQ(*s.precision, 0);
  EXPECT_FALSE(s.recall.has_value());
  s = ScoreShotBoundaries(Samples(100, {}, {}), 2);
  EXPECT_EQ(s.matched, 0);
  EXPECT_FALSE(s.precision.has_value());
  EXPECT_FALSE(s.recall.has_value());
}

TEST(ShotBoundaries, ToleranceIsInclusiveAndEachBoundaryCountsOnce) {
  EXPECT_EQ(ScoreShotBoundaries(Samples(100, {40}, {42}), 2).matched, 1);
  EXPECT_EQ(ScoreShotBoundaries(Samples(100, {40}, {43}), 2).matched, 0);
  EXPECT_EQ(ScoreShotBoundaries(Samples(100, {40}, {38}), 2).matched, 1);
  // Two estimated boundaries around one true cut: one matches, the other is extra.
  const ShotBoundaryScore s = ScoreShotBoundaries(Samples(100, {40}, {39, 41}), 2);
  EXPECT_EQ(s.matched, 1);
  EXPECT_DOUBLE_EQ(*s.precision, 0.5);
  EXPECT_DOUBLE_EQ(*s.recall, 1);
}

TEST(ShotBoundaries, GreedyMatchingIsMaximal) {
  // gt 10, 14; est 12, 16 with tolerance 2: 10-12 and 14-16 both match
  // (matching 14 to 12 first would leave 10 and 16 alone).
  const ShotBoundaryScore s = ScoreShotBoundaries(Samples(30, {10, 14}, {12, 16}), 2);
  EXPECT_EQ(s.matched, 2);
}

TEST(ShotBoundaries, GapsInTheMatchedFramesUseFrameNumbers) {
  // Frames 0..9 and 20..29 matched (the estimate skipped 10..19); the cut at
  // 15 shows at frame 20 in both.
  std::vector<ShotSample> v;
  for (int f = 0; f < 30; ++f) {
    if (f >= 10 && f < 20) continue;
    v.push_back({f, f >= 15, f >= 15});
  }
  const ShotBoundaryScore s = ScoreShotBoundaries(v, 0);
  EXPECT_EQ(s.gt_boundaries, std::vector<int>({20}));
  EXPECT_EQ(s.matched, 1);
}

}  // namespace
}  // namespace hapcine
