#include "bench/bench_results.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include <fstream>

#include "core/error.h"

namespace hapcine::bench {
namespace {

namespace fs = std::filesystem;

fs::path TempDir() {
  const fs::path d = fs::temp_directory_path() / ("hapcine_bench_results_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

const char* kHeader = "group\ttool\tsetting\tclip\trc\twall_s\tuser_s\tsys_s\tmaxrss_kb\tframes\teval_json\tnote\n";

TEST(ReadRuns, JoinsTheEvalReport) {
  const fs::path d = TempDir();
  {
    std::ofstream(d / "e.json") << R"({"frames":{"matched":100,"gt":168},
      "overall":{"rotation_deg":{"mean":0.5},"fov_percent":{"mean":1.0},
      "zoom_ratio_percent":{"mean":0.1},"ate_percent":null,"gt_static":true}})";
    std::ofstream(d / "runs.tsv") << kHeader
        << "accuracy\thapcine\t960 (default)\tzoom_in\t0\t16.8\t20\t1\t150000\t168\te.json\t\n"
        << "accuracy\tcolmap\t\ttilting\t1\t5\t4\t1\t90000\t168\t\tmapper failed\n";
  }
  const auto rows = ReadRuns((d / "runs.tsv").string());
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_TRUE(rows[0].eval);
  EXPECT_DOUBLE_EQ(rows[0].eval->rotation_deg, 0.5);
  EXPECT_FALSE(rows[0].eval->ate_percent);
  EXPECT_TRUE(rows[0].Partial());  // 100 of 168 frames
  EXPECT_FALSE(rows[0].Failed());
  EXPECT_NEAR(rows[0].MsPerFrame(), 100, 1e-9);
  EXPECT_EQ(rows[0].Method(), "hapcine 960 (default)");
  EXPECT_TRUE(rows[1].Failed());
  EXPECT_EQ(rows[1].note, "mapper failed");
  fs::remove_all(d);
}

TEST(ReadRuns, MalformedRowNamesTheLine) {
  const fs::path d = TempDir();
  std::ofstream(d / "bad.tsv") << kHeader << "accuracy\thapcine\tx\n";
  try {
    ReadRuns((d / "bad.tsv").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.tsv:2"), std::string::npos);
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace hapcine::bench
