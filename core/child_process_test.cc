#include "core/child_process.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "core/stop_signal.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

std::string LogPath(const std::string& name) {
  const fs::path dir = fs::path(HAPCINE_BINARY_DIR) / "child_process_test";
  fs::create_directories(dir);
  const fs::path log = dir / (name + ".log");
  fs::remove(log);
  return log.string();
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(ChildProcess, ExitCodeAndBothStreamsInTheLog) {
  const std::string log = LogPath("exit3");
  const ChildResult r = RunChild({"sh", "-c", "echo out; echo err >&2; exit 3"}, log);
  EXPECT_TRUE(r.started);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.term_signal, 0);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(Read(log), "out\nerr\n");
  // Appended, not truncated.
  EXPECT_TRUE(RunChild({"sh", "-c", "echo again"}, log).ok());
  EXPECT_EQ(Read(log), "out\nerr\nagain\n");
}

TEST(ChildProcess, MissingProgramIsNotStarted) {
  const ChildResult r = RunChild({"hapcine-no-such-program-xyz"}, LogPath("missing"));
  EXPECT_FALSE(r.started);
  EXPECT_EQ(r.start_errno, ENOENT);
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(RunChild({}, LogPath("empty")).started);
}

TEST(ChildProcess, StopRequestTerminatesTheChild) {
  ClearStopRequest();
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    RequestStop();
  });
  const ChildResult r = RunChild({"sleep", "60"}, LogPath("stop"));
  stopper.join();
  ClearStopRequest();
  EXPECT_TRUE(r.started);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.term_signal, SIGTERM);
  EXPECT_FALSE(r.ok());
}

TEST(ChildProcess, ChildIgnoringSigtermIsKilledAfterTheGrace) {
  ClearStopRequest();
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    RequestStop();
  });
  // `exec` keeps the ignored SIGTERM in the program that replaces the shell.
  const ChildResult r =
      RunChild({"sh", "-c", "trap '' TERM; exec sleep 60"}, LogPath("ignore"), 0.2);
  stopper.join();
  ClearStopRequest();
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.term_signal, SIGKILL);
}

TEST(ChildProcess, RealSigtermToTheParentStopsTheChild) {
  ClearStopRequest();
  ScopedStopSignals signals;
  std::thread sender([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    kill(getpid(), SIGTERM);  // the handler is installed: only the flag is set
  });
  const ChildResult r = RunChild({"sleep", "60"}, LogPath("sigterm"));
  sender.join();
  EXPECT_EQ(StopSignal(), SIGTERM);
  ClearStopRequest();
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.term_signal, SIGTERM);
}

}  // namespace
}  // namespace hapcine
