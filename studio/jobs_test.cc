#include "studio/jobs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "core/error.h"

namespace hapcine::studio {
namespace {

// Waits (without a deadline of its own: gtest's timeout bounds it) until the
// job leaves `running`.
JobStatus WaitForEnd(const JobRegistry& jobs, const std::string& id) {
  for (;;) {
    const JobStatus s = *jobs.Status(id);
    if (s.state != JobState::kRunning) return s;
    std::this_thread::yield();
  }
}

TEST(Jobs, ReportProgressWithAnEtaThenTheirPath) {
  JobRegistry jobs;
  std::atomic<bool> halfway{false}, release{false};
  const std::string id = jobs.Start([&](const JobProgressFn& progress) {
    progress(0.5);
    halfway = true;
    while (!release) std::this_thread::yield();
    return std::string("/out/film.preview.mp4");
  });
  while (!halfway) std::this_thread::yield();
  const JobStatus running = *jobs.Status(id);
  EXPECT_EQ(running.state, JobState::kRunning);
  EXPECT_EQ(running.progress, 0.5);
  ASSERT_TRUE(running.eta_s);
  EXPECT_GE(*running.eta_s, 0.0);
  EXPECT_EQ(running.ToJson()["state"], "running");
  release = true;
  const JobStatus done = WaitForEnd(jobs, id);
  EXPECT_EQ(done.state, JobState::kDone);
  EXPECT_EQ(done.progress, 1.0);
  EXPECT_EQ(done.path, "/out/film.preview.mp4");
  EXPECT_TRUE(done.ToJson()["eta_s"].is_null());
  EXPECT_FALSE(jobs.Status("j999"));
}

TEST(Jobs, AFailureIsItsOneLine) {
  JobRegistry jobs;
  const std::string id = jobs.Start([](const JobProgressFn&) -> std::string {
    throw Error("film.mp4", "not a media file");
  });
  const JobStatus failed = WaitForEnd(jobs, id);
  EXPECT_EQ(failed.state, JobState::kFailed);
  EXPECT_EQ(failed.error, "film.mp4: not a media file");
  EXPECT_EQ(failed.ToJson()["state"], "failed");
}

TEST(Jobs, StartOnceRunsAKeyOnceUnlessItFailed) {
  JobRegistry jobs;
  std::atomic<int> runs{0};
  auto work = [&](const JobProgressFn&) {
    ++runs;
    return std::string("p");
  };
  const std::string a = jobs.StartOnce("proxy:f0", work);
  WaitForEnd(jobs, a);
  EXPECT_EQ(jobs.StartOnce("proxy:f0", work), a);
  EXPECT_NE(jobs.StartOnce("proxy:f1", work), a);
  const std::string failing = jobs.StartOnce("proxy:f2", [](const JobProgressFn&) -> std::string {
    throw std::runtime_error("ffmpeg failed");
  });
  WaitForEnd(jobs, failing);
  EXPECT_NE(jobs.StartOnce("proxy:f2", work), failing);  // a failed key may be retried
}

}  // namespace
}  // namespace hapcine::studio
