#include "core/diagnostics.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace hapcine {
namespace {

TEST(JsonDiagnostics, CollectsRecordsPerKindInArrivalOrderAfterTheHeader) {
  JsonDiagnostics d;
  d.Record("window", {{"first_frame", 0}});
  d.Record("window", {{"first_frame", 24}});
  d.Record("track_rms", {{"tracks", 3}});  // ends in "s": its own plural
  const nlohmann::json doc = d.Document({{"format", "x"}, {"windows", nlohmann::json::array()}});
  EXPECT_EQ(doc.at("format"), "x");
  ASSERT_EQ(doc.at("windows").size(), 2u);
  EXPECT_EQ(doc.at("windows")[1].at("first_frame"), 24);
  EXPECT_EQ(doc.at("track_rms")[0].at("tracks"), 3);
}

TEST(JsonDiagnostics, KeepsOnlyTheKindsItWants) {
  JsonDiagnostics d({"window"});
  EXPECT_TRUE(d.Wants("window"));
  EXPECT_FALSE(d.Wants("cut_cues"));
  d.Record("cut_cues", {{"frame", 1}});
  EXPECT_FALSE(d.Document().contains("cut_cuess"));
  EXPECT_FALSE(d.Document().contains("cut_cues"));
  // No sink: nothing is wanted, nothing happens.
  EXPECT_FALSE(Wants(nullptr, "window"));
  Record(nullptr, "window", {{"a", 1}});
}

TEST(JsonDiagnostics, TakesRecordsFromSeveralThreads) {
  JsonDiagnostics d;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&d, t] {
      for (int i = 0; i < 100; ++i) d.Record("stage", {{"thread", t}});
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(d.Document().at("stages").size(), 400u);
}

TEST(StageLog, RecordsEachStageWithWallAndCpuSeconds) {
  JsonDiagnostics d;
  StageLog log(&d);
  log.Stage("start");
  log.Stage("done");
  const nlohmann::json stages = d.Document().at("stages");
  ASSERT_EQ(stages.size(), 2u);
  EXPECT_EQ(stages[1].at("name"), "done");
  EXPECT_GE(stages[1].at("wall_s").get<double>(), stages[0].at("wall_s").get<double>());
  EXPECT_GE(stages[0].at("thread_cpu_s").get<double>(), 0);
  StageLog none(nullptr);
  none.Stage("nothing");  // no sink: no-op
}

}  // namespace
}  // namespace hapcine
