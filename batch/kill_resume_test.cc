// SIGKILL a running batch (its whole process group: the batch and the steps
// it is running) at a moment when some films are finished and others are
// half-way, then resume it: every film must end up done exactly once, with
// nothing lost, nothing redone that was finished, no temporary file left and
// a correct summary.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <thread>

#include "batch/batch.h"
#include "batch/fake_step_for_test.h"
#include "batch/library.h"
#include "batch/state_files.h"

namespace hapcine::batch {
namespace {
namespace fs = std::filesystem;

using testutil::LogLines;
using testutil::MakeTestLibrary;
using testutil::OutputFiles;
using testutil::TempDir;
using testutil::TempLeftovers;
using testutil::TestLibrary;
using testutil::WriteFakeStep;
using testutil::WriteFile;

int CountDone(const BatchOptions& o, std::set<std::string>* done_ids) {
  int n = 0;
  std::error_code ec;  // the folder may not exist yet
  for (const auto& e : fs::directory_iterator(o.out_dir, ec)) {
    if (fs::exists(e.path() / "done.json")) {
      ++n;
      if (done_ids) done_ids->insert(e.path().filename().string());
    }
  }
  return n;
}

TEST(KillResumeTest, SigkillMidwayThenResumeLosesAndDuplicatesNothing) {
  TempDir dir("batch_kill");
  TestLibrary lib = MakeTestLibrary(dir.path() + "/library");
  for (int i = 0; i < 7; ++i) {  // more good films, so the kill lands mid-batch
    const std::string name = "more " + std::to_string(i) + ".mp4";
    WriteFile(lib.root + "/" + name, "FAKEVIDEO " + name + "\n");
    lib.good.push_back(name);
  }
  const std::string log = dir.path() + "/calls.log";
  BatchOptions o;
  o.library = lib.root;
  o.out_dir = dir.path() + "/out";
  o.jobs = 2;
  o.step_exe = WriteFakeStep(dir.path(), log, /*estimate_delay_s=*/0.2);
  o.progress = BatchOptions::Progress::kQuiet;

  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group: killed below with every step it runs
    try {
      RunLocalBatch(o);
    } catch (...) {
    }
    ::_exit(0);
  }
  ::setpgid(pid, pid);  // no race with the child's own call
  // Wait until some films are finished and steps are running.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (CountDone(o, nullptr) < 3 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // steps mid-way
  ASSERT_EQ(::killpg(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // let killed steps go

  std::set<std::string> done_before;
  const int n_done_before = CountDone(o, &done_before);
  ASSERT_GE(n_done_before, 3);
  ASSERT_LT(n_done_before, static_cast<int>(lib.good.size())) << "kill came too late to test";
  EXPECT_FALSE(fs::exists(o.out_dir + "/summary.json"));  // the killed run never finished
  // Every done.json left by the killed run is complete and its outputs intact.
  for (const std::string& id : done_before) {
    const auto done = ReadJsonFile(o.out_dir + "/" + id + "/done.json");
    ASSERT_TRUE(done.has_value()) << id;
    for (const auto& out : (*done)["outputs"]) {
      EXPECT_EQ(fs::file_size(o.out_dir + "/" + id + "/" + out["file"].get<std::string>()),
                out["bytes"].get<uint64_t>());
    }
  }
  const size_t calls_before = LogLines(log, "estimate ").size();

  const BatchSummary s = RunLocalBatch(o);
  const int n_good = static_cast<int>(lib.good.size());
  EXPECT_EQ(s.Count(FilmStatus::kSkipped), n_done_before);
  EXPECT_EQ(s.Count(FilmStatus::kDone), n_good - n_done_before);
  EXPECT_EQ(s.Count(FilmStatus::kFailed), 3);
  EXPECT_EQ(s.Count(FilmStatus::kDuplicate), 1);
  EXPECT_EQ(static_cast<int>(s.films.size()), lib.total());
  EXPECT_EQ(CountDone(o, nullptr), n_good);
  EXPECT_TRUE(TempLeftovers(o.out_dir).empty());

  // Nothing finished was redone: the resumed run estimated only films that
  // had no done.json, each once, or reused a camera path whose step had
  // finished (stamp written) before the kill.
  const std::vector<std::string> calls = LogLines(log, "estimate ");
  std::multiset<std::string> resumed(calls.begin() + calls_before, calls.end());
  int reused_estimates = 0;
  for (const FilmOutcome& f : s.films) {
    if (f.status != FilmStatus::kDone) continue;
    EXPECT_EQ(done_before.count(f.id), 0u) << f.path << " was done before the kill";
    ASSERT_FALSE(f.steps.empty());
    const size_t n_calls = resumed.count("estimate " + f.path);
    EXPECT_EQ(n_calls, f.steps[0].reused ? 0u : 1u) << f.path;
    reused_estimates += f.steps[0].reused;
  }
  EXPECT_EQ(static_cast<int>(resumed.size()) + reused_estimates, n_good - n_done_before);
  // The outputs equal an uninterrupted run's, byte for byte.
  BatchOptions clean = o;
  clean.out_dir = dir.path() + "/clean";
  clean.jobs = 4;
  clean.step_exe = WriteFakeStep(dir.path() + "/no-delay", dir.path() + "/clean-calls.log");
  RunLocalBatch(clean);
  EXPECT_EQ(OutputFiles(o.out_dir), OutputFiles(clean.out_dir));
  const BatchStatus st = ReadBatchStatus(o.out_dir);
  EXPECT_EQ(st.done, n_good);
  EXPECT_EQ(st.pending + st.running, 0);
}

}  // namespace
}  // namespace hapcine::batch
