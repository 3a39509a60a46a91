#include "extract/keep_tracks.h"

#include <gtest/gtest.h>

namespace hapcine {
namespace {

TEST(KeepTracksIf, KeepsTheMarkedTracksInOrder) {
  std::vector<cv::Point2f> points{{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  std::vector<long> ids{10, 11, 12, 13};
  std::vector<size_t> asked;
  KeepTracksIf(&points, &ids, [&](size_t i) {
    asked.push_back(i);
    return i % 2 == 1;
  });
  EXPECT_EQ(asked, (std::vector<size_t>{0, 1, 2, 3}));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(ids, (std::vector<long>{11, 13}));
  EXPECT_EQ(points[0], cv::Point2f(1, 1));
  EXPECT_EQ(points[1], cv::Point2f(3, 3));
}

TEST(KeepTracksIf, NoneAndAllAndEmpty) {
  std::vector<cv::Point2f> points{{0, 0}, {1, 1}};
  std::vector<long> ids{1, 2};
  KeepTracksIf(&points, &ids, [](size_t) { return true; });
  EXPECT_EQ(ids, (std::vector<long>{1, 2}));
  KeepTracksIf(&points, &ids, [](size_t) { return false; });
  EXPECT_TRUE(points.empty());
  EXPECT_TRUE(ids.empty());
  KeepTracksIf(&points, &ids, [](size_t) { return true; });
  EXPECT_TRUE(ids.empty());
}

}  // namespace
}  // namespace hapcine
