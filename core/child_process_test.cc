#include "core/child_process.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "core/error.h"
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

ChildOptions Stoppable(double grace_s = 5.0) {
  ChildOptions o;
  o.stop_on_request = true;
  o.grace_s = grace_s;
  return o;
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(ChildProcess, ExitCodeAndBothStreamsInTheLog) {
  const std::string log = LogPath("exit3");
  ChildOptions append;
  append.append_log = true;
  const ChildResult r = RunChild({"sh", "-c", "echo out; echo err >&2; exit 3"}, log, append);
  EXPECT_TRUE(r.started);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.term_signal, 0);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(Read(log), "out\nerr\n");
  EXPECT_GE(r.seconds, 0.0);
  EXPECT_TRUE(RunChild({"sh", "-c", "echo again"}, log, append).ok());
  EXPECT_EQ(Read(log), "out\nerr\nagain\n");
  EXPECT_TRUE(RunChild({"sh", "-c", "echo fresh"}, log).ok());  // default: truncated
  EXPECT_EQ(Read(log), "fresh\n");
}

TEST(ChildProcess, StdinIsEmptyAndSignalsAreReported) {
  const std::string log = LogPath("stdin");
  EXPECT_TRUE(RunChild({"sh", "-c", "cat; echo end"}, log).ok());  // /dev/null: no wait
  EXPECT_EQ(Read(log), "end\n");
  const ChildResult r = RunChild({"sh", "-c", "kill -SEGV $$"}, log);
  EXPECT_EQ(r.term_signal, SIGSEGV);
  EXPECT_EQ(r.exit_code, -1);
  EXPECT_FALSE(r.ok());
}

TEST(ChildProcess, MissingProgramIsNotStarted) {
  const std::string log = LogPath("missing");
  const ChildResult r = RunChild({"hapcine-no-such-program-xyz"}, log);
  EXPECT_FALSE(r.started);
  EXPECT_EQ(r.start_errno, ENOENT);
  EXPECT_EQ(r.exit_code, 127);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(LastNonEmptyLine(log), "cannot execute step program: hapcine-no-such-program-xyz");
  EXPECT_THROW(RunChild({}, log), Error);
  EXPECT_THROW(RunChild({"true"}, LogPath("x") + "/no/such/dir/log"), Error);
}

TEST(ChildProcess, LastNonEmptyLineIsCutOnCharacterBoundary) {
  const std::string file = LogPath("long");
  std::string long_line;
  for (int i = 0; i < 300; ++i) long_line += "\xc3\xa9";  // e acute, 2 bytes
  std::ofstream(file) << "one\r\n" << long_line << "  \r\n\n";
  const std::string last = LastNonEmptyLine(file, 101);
  EXPECT_EQ(last.size(), 100u + 3u);  // 50 whole characters + "..."
  EXPECT_EQ(LastNonEmptyLine(LogPath("missing-file")), "");
}

TEST(ChildProcess, StopRequestTerminatesTheChild) {
  ClearStopRequest();
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    RequestStop();
  });
  const ChildResult r = RunChild({"sleep", "60"}, LogPath("stop"), Stoppable());
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
      RunChild({"sh", "-c", "trap '' TERM; exec sleep 60"}, LogPath("ignore"), Stoppable(0.2));
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
  const ChildResult r = RunChild({"sleep", "60"}, LogPath("sigterm"), Stoppable());
  sender.join();
  EXPECT_EQ(StopSignal(), SIGTERM);
  ClearStopRequest();
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.term_signal, SIGTERM);
}

}  // namespace
}  // namespace hapcine

