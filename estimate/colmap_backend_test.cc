// The COLMAP backend's failure paths with a fake `colmap` (a shell script):
// a failing step, a missing binary, and a stop request (SIGINT/SIGTERM) while
// frames are exported or while COLMAP runs. On every one: a one-line Error
// naming the video, the child gone, the temporary folder removed.

#include "estimate/colmap_backend.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <thread>

#include "core/error.h"
#include "core/stop_signal.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

// Gray frames from memory; `on_frame` runs before each frame is handed out.
class MemorySource : public FrameSource {
 public:
  explicit MemorySource(int frames, std::function<void(int)> on_frame = {})
      : frames_(frames), on_frame_(std::move(on_frame)) {
    info_.path = "memory.mp4";
    info_.width = 64;
    info_.height = 48;
    info_.fps = 24;
    info_.frame_count = frames;
  }
  const VideoInfo& info() const override { return info_; }
  bool Next(Frame* frame) override {
    if (next_ >= frames_) return false;
    if (on_frame_) on_frame_(next_);
    frame->index = next_;
    frame->time_s = next_ / 24.0;
    frame->gray = cv::Mat(48, 64, CV_8UC1, cv::Scalar(10 + 20 * next_));
    frame->bgr.release();
    ++next_;
    return true;
  }

 private:
  VideoInfo info_;
  int frames_, next_ = 0;
  std::function<void(int)> on_frame_;
};

class ColmapBackendTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ClearStopRequest();
    dir_ = fs::path(HAPCINE_BINARY_DIR) / "colmap_backend_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    tmp_ = dir_ / "tmp";
    fs::create_directories(tmp_);
    const char* old = std::getenv("TMPDIR");
    if (old) old_tmpdir_ = old;
    had_tmpdir_ = old != nullptr;
    setenv("TMPDIR", tmp_.c_str(), 1);  // where the backend makes its folder
  }
  void TearDown() override {
    if (had_tmpdir_) setenv("TMPDIR", old_tmpdir_.c_str(), 1);
    else unsetenv("TMPDIR");
    ClearStopRequest();
  }
  // A fake colmap running `body` (sh) for every step.
  std::string FakeColmap(const std::string& body) {
    const fs::path script = dir_ / "colmap";
    std::ofstream(script) << "#!/bin/sh\n" << body << "\n";
    chmod(script.c_str(), 0755);
    return script.string();
  }
  bool TmpIsEmpty() const { return fs::is_empty(tmp_); }

  fs::path dir_, tmp_;
  std::string old_tmpdir_;
  bool had_tmpdir_ = false;
};

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(ColmapBackendTest, FailingStepNamesTheVideoAndTheLastLogLine) {
  MemorySource source(3);
  const std::string colmap = FakeColmap("echo \"step $1\"; echo 'cannot read database' >&2; exit 1");
  EXPECT_EQ(MessageOf([&] { EstimateWithColmap(source, colmap, {}); }),
            "memory.mp4: colmap feature_extractor failed: cannot read database");
  EXPECT_TRUE(TmpIsEmpty());
}

TEST_F(ColmapBackendTest, MissingBinary) {
  MemorySource source(3);
  const std::string colmap = (dir_ / "no-colmap-here").string();
  EXPECT_EQ(MessageOf([&] { EstimateWithColmap(source, colmap, {}); }),
            "memory.mp4: colmap binary '" + colmap + "' not found");
  EXPECT_TRUE(TmpIsEmpty());
}

TEST_F(ColmapBackendTest, MapperThatInitialisesNothing) {
  MemorySource source(3);
  const std::string colmap = FakeColmap("exit 0");  // every step "succeeds", no model
  EXPECT_NE(MessageOf([&] { EstimateWithColmap(source, colmap, {}); })
                .find("memory.mp4: colmap mapper could not initialise a model"),
            std::string::npos);
  EXPECT_TRUE(TmpIsEmpty());
}

TEST_F(ColmapBackendTest, StopWhileExportingFrames) {
  MemorySource source(5, [](int i) {
    if (i == 2) RequestStop();
  });
  const std::string colmap = FakeColmap("exit 0");
  EXPECT_EQ(MessageOf([&] { EstimateWithColmap(source, colmap, {}); }),
            "memory.mp4: interrupted by a stop request during frame export");
  EXPECT_TRUE(TmpIsEmpty());
}

TEST_F(ColmapBackendTest, SigtermWhileColmapRunsKillsItAndCleansUp) {
  MemorySource source(3);
  const fs::path pid_file = dir_ / "child.pid";
  const std::string colmap = FakeColmap("echo $$ > '" + pid_file.string() + "'; exec sleep 60");
  std::thread sender([&] {
    for (int i = 0; i < 500 && !fs::exists(pid_file); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    kill(getpid(), SIGTERM);  // as `kill PID` or a scheduler would
  });
  const std::string message = MessageOf([&] { EstimateWithColmap(source, colmap, {}); });
  sender.join();
  EXPECT_EQ(message, "memory.mp4: interrupted by SIGTERM during colmap feature_extractor");
  EXPECT_TRUE(TmpIsEmpty());
  int child = 0;
  std::ifstream(pid_file) >> child;
  ASSERT_GT(child, 0);
  EXPECT_EQ(kill(child, 0), -1);  // the fake COLMAP is gone (and was reaped)
  EXPECT_EQ(errno, ESRCH);
}

}  // namespace
}  // namespace hapcine
