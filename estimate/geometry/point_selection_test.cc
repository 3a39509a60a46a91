#include "estimate/geometry/point_selection.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace hapcine {
namespace {

// A cluster of long tracks in one corner (a subject's outline) and shorter
// tracks spread over the rest of the image.
std::vector<TrackCandidate> OutlineAndBackground() {
  std::vector<TrackCandidate> c;
  long id = 0;
  for (int i = 0; i < 50; ++i) c.push_back({id++, 20, Eigen::Vector2d(0.01 * (i % 10), 0.01 * (i / 10))});
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) c.push_back({id++, 5, Eigen::Vector2d(0.1 * x + 0.05, 0.1 * y + 0.05)});
  return c;
}

bool IsOutline(long id) { return id < 50; }

TEST(SelectWindowTracks, WithoutGridTakesTheLongestTracks) {
  const auto ids = SelectWindowTracks(OutlineAndBackground(), 40, 0);
  ASSERT_EQ(ids.size(), 40u);
  for (long id : ids) EXPECT_TRUE(IsOutline(id)) << id;
}

TEST(SelectWindowTracks, GridGivesEveryCellItsShare) {
  const auto ids = SelectWindowTracks(OutlineAndBackground(), 40, 4);
  ASSERT_EQ(ids.size(), 40u);
  // 16 cells, 40 points: at most 3 turns, so the outline's cell gives at most 3.
  const long outline = std::count_if(ids.begin(), ids.end(), IsOutline);
  EXPECT_GE(outline, 1);
  EXPECT_LE(outline, 3);
  // The first turn takes each cell's longest track, the outline's first.
  EXPECT_TRUE(IsOutline(ids.front()));
}

TEST(SelectWindowTracks, TakesEverythingWhenThereIsRoom) {
  auto c = OutlineAndBackground();
  auto ids = SelectWindowTracks(c, 1000, 6);
  ASSERT_EQ(ids.size(), c.size());
  std::sort(ids.begin(), ids.end());
  for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(ids[i], static_cast<long>(i));
}

TEST(SelectWindowTracks, DegenerateInputs) {
  EXPECT_TRUE(SelectWindowTracks({}, 10, 6).empty());
  // All candidates at one spot (zero-size bounding box): one cell, longest first, no NaN.
  std::vector<TrackCandidate> same = {{1, 3, {0.2, 0.2}}, {2, 9, {0.2, 0.2}}, {3, 5, {0.2, 0.2}}};
  EXPECT_EQ(SelectWindowTracks(same, 2, 6), (std::vector<long>{2, 3}));
  EXPECT_TRUE(SelectWindowTracks(same, 0, 6).empty());
}

}  // namespace
}  // namespace hapcine
