#include "estimate/estimator_records.h"

#include <gtest/gtest.h>

#include <vector>

namespace hapcine {
namespace {

// Collects what reaches the sink.
class Sink : public Diagnostics {
 public:
  bool Wants(const std::string&) const override { return true; }
  void Record(const std::string& kind, nlohmann::json fields) override {
    records.emplace_back(kind, std::move(fields));
  }
  std::vector<std::pair<std::string, nlohmann::json>> records;
};

TEST(EstimatorRecords, HeldUntilReleasedThenInThePathsNumbers) {
  Sink sink;
  EstimatorRecords records(&sink);
  records.Record("window", {{"shot", 0},
                            {"first_frame", 0},
                            {"last_frame", 2},
                            {"keyframes", {{{"frame", 0}}, {{"frame", 2}}}},
                            {"points", 7}});
  EXPECT_TRUE(sink.records.empty());
  // Positions 0, 1, 2 were frames 14, 15, 0 (a ring of stills come round);
  // the estimator's shot 0 is the path's shot 1.
  records.Release({14, 15, 0}, {{0, 1}});
  ASSERT_EQ(sink.records.size(), 1u);
  const nlohmann::json& w = sink.records[0].second;
  EXPECT_EQ(w.at("shot"), 1);
  EXPECT_EQ(w.at("first_frame"), 14);
  EXPECT_EQ(w.at("last_frame"), 0);
  EXPECT_EQ(w.at("keyframes")[0].at("frame"), 14);
  EXPECT_EQ(w.at("keyframes")[1].at("frame"), 0);
  EXPECT_EQ(w.at("points"), 7);                    // not a frame: kept
  records.Record("window", {{"first_frame", 1}});  // after the release: passed on as is
  ASSERT_EQ(sink.records.size(), 2u);
  EXPECT_EQ(sink.records[1].second.at("first_frame"), 1);
}

TEST(EstimatorRecords, NumbersOutsideTheMapsAreKept) {
  Sink sink;
  EstimatorRecords records(&sink);
  records.Record("track_drifts", {{"first_frame", 5}, {"shot", 3}, {"frame", -1}});
  records.Release({10, 11}, {});
  const nlohmann::json& r = sink.records.at(0).second;
  EXPECT_EQ(r.at("first_frame"), 5);  // no such position: unchanged, not a crash
  EXPECT_EQ(r.at("shot"), 3);
  EXPECT_EQ(r.at("frame"), -1);
}

TEST(EstimatorRecords, NoSinkListensToNothing) {
  EstimatorRecords records(nullptr);
  EXPECT_FALSE(records.Wants("window"));
  records.Record("window", {{"frame", 0}});
  records.Release({3}, {});  // nothing to pass on, nowhere to pass it
}

TEST(ShotNumbers, FromEachFramesShotBeforeAndAfter) {
  CameraPath path;
  for (int f : {0, 1, 2}) {
    CameraFrame frame;
    frame.frame = f;
    frame.shot = f == 1 ? 1 : 0;
    path.frames.push_back(frame);
  }
  path.frames.push_back(CameraFrame{});  // no shot: left out
  path.frames.back().frame = 3;
  const std::map<int, int> before = ShotOfFrame(path);
  EXPECT_EQ(before.size(), 3u);
  const std::map<int, int> after = {{0, 1}, {1, 0}, {2, 1}};
  const std::map<int, int> numbers = ShotNumbers(before, after);
  EXPECT_EQ(numbers, (std::map<int, int>{{0, 1}, {1, 0}}));
}

}  // namespace
}  // namespace hapcine
