#include "batch/slurm.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "batch/fake_step_for_test.h"
#include "batch/library.h"
#include "batch/state_files.h"
#include "core/error.h"

namespace hapcine::batch {
namespace {
namespace fs = std::filesystem;

using testutil::TempDir;

TEST(SlurmTest, ShellQuoteRoundTripsThroughSplitArgs) {
  EXPECT_EQ(ShellQuote("a b"), "'a b'");
  EXPECT_EQ(ShellQuote("it's"), "'it'\\''s'");
  for (const std::string w : {"plain", "with space", "it's", "日本 é", "$HOME", "a\"b", ""}) {
    EXPECT_EQ(SplitArgs(ShellQuote(w)), std::vector<std::string>{w}) << w;
  }
}

TEST(SlurmTest, JobScriptRunsOneShardPerTaskAndWritesItsStatus) {
  BatchOptions o;
  o.library = "/lib";
  o.out_dir = "/data/out dir/it's";
  o.jobs = 2;
  o.models = {"cinematic"};
  o.step_exe = "/opt/hapcine";
  o.estimate_args = {"--max-frames", "10 20"};
  SlurmOptions s;
  s.batch_exe = "/usr/bin/hapcine";
  const std::string script = SlurmJobScript(o, s, "/data/out dir/it's/.batch/library.txt", 4);
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("'/usr/bin/hapcine' 'batch' '/data/out dir/it'\\''s/.batch/library.txt' "
                        "'-o' '/data/out dir/it'\\''s' '--jobs' '2' '--models' 'cinematic' "
                        "'--hapcine-exe' '/opt/hapcine' '--progress' 'lines' "
                        "'--estimate-args' ''\\''--max-frames'\\'' '\\''10 20'\\''' "
                        "--shard \"$i/4\"\n"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("task-$i.status"), std::string::npos);
  EXPECT_NE(script.find("exit $rc"), std::string::npos);
}

TEST(SlurmTest, MissingShardSummaryMarksItsFilmsFailed) {
  TempDir d;
  BatchOptions o;
  o.library = "/lib";
  o.out_dir = d.path();
  BatchPlan plan;
  plan.shard_count = 2;
  plan.films = {{"/lib/a.mp4", "a-1", "a", 1, "h", "", "", 0},
                {"/lib/b.mp4", "b-2", "b", 1, "h2", "", "", 1}};
  BatchSummary shard0;
  shard0.shard_count = 2;
  FilmOutcome a;
  a.id = "a-1";
  a.path = "/lib/a.mp4";
  a.status = FilmStatus::kDone;
  shard0.films = {a};
  fs::create_directories(d.path() + "/.batch/shards");
  WriteJsonAtomic(d.path() + "/.batch/shards/summary-0-of-2.json", shard0.ToJson());
  const BatchSummary merged = MergeShardSummaries(o, plan);
  ASSERT_EQ(merged.films.size(), 2u);
  EXPECT_EQ(merged.films[0].status, FilmStatus::kDone);
  EXPECT_EQ(merged.films[1].status, FilmStatus::kFailed);
  EXPECT_NE(merged.films[1].reason.find("slurm task 1 wrote no summary"), std::string::npos);
  EXPECT_EQ(merged.ExitCode(), 1);
}

TEST(SlurmTest, OptionsCheck) {
  SlurmOptions s;
  EXPECT_NO_THROW(s.Check());
  s.shards = 0;
  EXPECT_THROW(s.Check(), UsageError);
}

}  // namespace
}  // namespace hapcine::batch
