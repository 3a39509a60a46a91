#include "core/output_files.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/stop_signal.h"

namespace hapcine {
namespace {
namespace fs = std::filesystem;

std::string Slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

void WriteAtomic(const std::string& path, const std::string& text) {
  AtomicFile f(path);
  f.stream() << text;
  f.Commit();
}

std::vector<std::string> Temps(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (ParseTempName(e.path().filename().string(), nullptr, nullptr))
      found.push_back(e.path().filename().string());
  }
  return found;
}

class OutputFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / ("output_files_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(OutputFilesTest, TempNameIsShortInTheTargetFolderAndParses) {
  AtomicFile f(P("out.csv"));
  const fs::path temp(f.temp_path());
  EXPECT_EQ(temp.parent_path(), dir_);
  EXPECT_LT(temp.filename().string().size(), 40u);
  long pid = 0;
  bool here = false;
  ASSERT_TRUE(ParseTempName(temp.filename().string(), &pid, &here));
  EXPECT_EQ(pid, ::getpid());
  EXPECT_TRUE(here);
  EXPECT_FALSE(ParseTempName("out.csv", nullptr, nullptr));
  EXPECT_FALSE(ParseTempName(".12-3-xyz.hapcine-tmp", nullptr, nullptr));
}

TEST_F(OutputFilesTest, TwoWritersOfOnePathGetDistinctTemporaries) {
  AtomicFile a(P("x")), b(P("x"));
  EXPECT_NE(a.temp_path(), b.temp_path());
}

TEST_F(OutputFilesTest, A250ByteNameIsWritten) {
  const std::string name(250, 'n');
  WriteAtomic(P(name), "long");
  EXPECT_EQ(Slurp(P(name)), "long");
  EXPECT_TRUE(Temps(dir_).empty());
}

TEST_F(OutputFilesTest, SymlinkIsFollowedAndStays) {
  fs::create_directories(dir_ / "real");
  WriteText(dir_ / "real" / "t.csv", "old");
  fs::create_symlink("real/t.csv", dir_ / "hop");
  fs::create_symlink("hop", dir_ / "link.csv");  // a chain of two links
  WriteAtomic(P("link.csv"), "new");
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.csv"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "hop"));
  EXPECT_EQ(Slurp(dir_ / "real" / "t.csv"), "new");
  EXPECT_TRUE(Temps(dir_).empty());
  EXPECT_TRUE(Temps(dir_ / "real").empty());
}

TEST_F(OutputFilesTest, DanglingSymlinkCreatesItsTarget) {
  fs::create_symlink("made.csv", dir_ / "link.csv");
  WriteAtomic(P("link.csv"), "x");
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.csv"));
  EXPECT_EQ(Slurp(dir_ / "made.csv"), "x");
}

TEST_F(OutputFilesTest, DeviceNodeIsWrittenDirectlyAndStaysADevice) {
  if (::geteuid() != 0) GTEST_SKIP() << "mknod needs root";
  const std::string null = P("null");
  if (::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) GTEST_SKIP() << "mknod refused";
  WriteAtomic(null, "into the void");
  struct stat st {};
  ASSERT_EQ(::stat(null.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  EXPECT_EQ(st.st_rdev, makedev(1, 3));
  EXPECT_TRUE(Temps(dir_).empty());
  // Two outputs on one device are harmless, so they are not refused.
  EXPECT_NO_THROW(CheckOutputPaths({}, {{null, "-o"}, {null, "--hjif"}}));
}

TEST_F(OutputFilesTest, FifoIsWrittenDirectly) {
  const std::string fifo = P("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string got;
  std::thread reader([&] { got = Slurp(fifo); });
  WriteAtomic(fifo, "through the pipe");
  reader.join();
  EXPECT_EQ(got, "through the pipe");
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(Temps(dir_).empty());
}

TEST_F(OutputFilesTest, DirectoryTargetIsAnErrorNamingIt) {
  fs::create_directories(dir_ / "d");
  try {
    AtomicFile f(P("d"));
    FAIL() << "a directory was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), P("d"));
  }
  EXPECT_THROW(CheckOutputPaths({}, {{P("d"), "--hjif"}}), Error);
  EXPECT_TRUE(Temps(dir_).empty());
}

TEST_F(OutputFilesTest, MissingOutputFolderIsAnErrorUpFront) {
  EXPECT_THROW(CheckOutputPaths({}, {{P("no/such/x.csv"), "-o"}}), Error);
}

TEST_F(OutputFilesTest, OutputThatIsTheInputIsAUsageErrorNamingBoth) {
  WriteText(dir_ / "in.csv", "data");
  ASSERT_EQ(::link(P("in.csv").c_str(), P("hard.csv").c_str()), 0);
  fs::create_symlink("in.csv", dir_ / "soft.csv");
  for (const std::string& out : {P("in.csv"), P("hard.csv"), P("soft.csv"),
                                 (dir_ / "." / "in.csv").string()}) {
    try {
      CheckOutputPaths({{P("in.csv"), "INPUT"}}, {{out, "-o"}});
      FAIL() << out << " was accepted as output of its own input";
    } catch (const UsageError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(out), std::string::npos) << m;
      EXPECT_NE(m.find(P("in.csv")), std::string::npos) << m;
    }
  }
  EXPECT_EQ(Slurp(dir_ / "in.csv"), "data");
  EXPECT_NO_THROW(CheckOutputPaths({{P("in.csv"), "INPUT"}}, {{P("out.csv"), "-o"}}));
}

TEST_F(OutputFilesTest, TwoOutputsOnOnePathAreAUsageError) {
  try {
    CheckOutputPaths({}, {{P("out.csv"), "-o"}, {(dir_ / "." / "out.csv").string(), "--hjif"}});
    FAIL() << "two outputs on one path were accepted";
  } catch (const UsageError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("-o"), std::string::npos) << m;
    EXPECT_NE(m.find("--hjif"), std::string::npos) << m;
  }
  // Through a link whose target does not exist yet.
  fs::create_symlink("new.csv", dir_ / "link.csv");
  EXPECT_THROW(CheckOutputPaths({}, {{P("link.csv"), "-o"}, {P("new.csv"), "--hjif"}}), UsageError);
  EXPECT_NO_THROW(CheckOutputPaths({}, {{P("a.csv"), "-o"}, {P("b.csv"), "--hjif"}}));
}

TEST_F(OutputFilesTest, SetCommitsNothingUntilCommitAll) {
  {
    OutputSet set({}, {{P("a"), "-o"}, {P("b"), "--hjif"}});
    WriteAtomic(P("a"), "A");
    WriteAtomic(P("b"), "B");
    EXPECT_FALSE(fs::exists(dir_ / "a"));
    EXPECT_FALSE(fs::exists(dir_ / "b"));
    set.CommitAll();
  }
  EXPECT_EQ(Slurp(dir_ / "a"), "A");
  EXPECT_EQ(Slurp(dir_ / "b"), "B");
  EXPECT_TRUE(Temps(dir_).empty());
  WriteAtomic(P("c"), "C");  // no set alive: committed at once
  EXPECT_EQ(Slurp(dir_ / "c"), "C");
}

TEST_F(OutputFilesTest, SetWhoseSecondOutputFailsCommitsNone) {
  WriteText(dir_ / "a", "old");
  try {
    OutputSet set({}, {{P("a"), "-o"}, {P("b"), "--per-frame"}});
    WriteAtomic(P("a"), "new");
    AtomicFile b(P("b"));
    b.stream() << "half";
    throw Error(P("b"), "failed half-way");
  } catch (const Error&) {
  }
  EXPECT_EQ(Slurp(dir_ / "a"), "old");
  EXPECT_FALSE(fs::exists(dir_ / "b"));
  EXPECT_TRUE(Temps(dir_).empty());
}

TEST_F(OutputFilesTest, NestedSetHandsItsFilesToTheOuterOne) {
  {
    OutputSet outer({}, {});
    {
      OutputSet inner({}, {});
      WriteAtomic(P("a"), "A");
      inner.CommitAll();
    }
    EXPECT_FALSE(fs::exists(dir_ / "a"));
    outer.CommitAll();
  }
  EXPECT_EQ(Slurp(dir_ / "a"), "A");
}

TEST_F(OutputFilesTest, SweepRemovesOnlyThisHostsTemporariesOfDeadProcesses) {
  long pid = 0;
  bool here = false;
  std::string own;
  {
    AtomicFile probe(P("probe"));  // this host's tag, from a live name
    own = fs::path(probe.temp_path()).filename().string();
    ASSERT_TRUE(ParseTempName(own, &pid, &here));
  }
  const std::string tail = own.substr(own.find('-'));  // "-<n>-<host>.hapcine-tmp"
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // now a dead pid
  const fs::path sub = dir_ / "sub";
  fs::create_directories(sub);
  const std::string dead = "." + std::to_string(child) + tail;
  const std::string live = "." + std::to_string(::getppid()) + tail;
  const std::string own_host = own.substr(own.rfind('-') + 1, 8);
  const std::string other_host = own_host == "ffffffff" ? "00000000" : "ffffffff";
  const std::string foreign = "." + std::to_string(child) + "-0-" + other_host + ".hapcine-tmp";
  for (const std::string& n : {dead, live, foreign, std::string("keep.tmp")}) WriteText(sub / n, "x");
  WriteAtomic((sub / "new.csv").string(), "y");  // the first temporary in sub sweeps it
  EXPECT_FALSE(fs::exists(sub / dead));
  EXPECT_TRUE(fs::exists(sub / live));
  EXPECT_TRUE(fs::exists(sub / foreign));  // another host's pid says nothing here
  EXPECT_TRUE(fs::exists(sub / "keep.tmp"));
}

// A child killed by SIGTERM while writing leaves no temporary.
TEST_F(OutputFilesTest, SigtermRemovesTheTemporary) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const std::string target = P("killed.csv");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(fds[0]);
    InstallTempCleanupOnSignals();
    AtomicFile f(target);
    f.stream() << "partial" << std::flush;
    const std::string temp = f.temp_path() + "\n";
    if (::write(fds[1], temp.data(), temp.size()) < 0) ::_exit(3);
    for (;;) ::pause();
  }
  ::close(fds[1]);
  std::string temp;
  char c;
  while (::read(fds[0], &c, 1) == 1 && c != '\n') temp += c;
  ::close(fds[0]);
  ASSERT_FALSE(temp.empty());
  EXPECT_TRUE(fs::exists(temp));
  ::kill(child, SIGTERM);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_FALSE(fs::exists(target));
}

// With the stop handlers of play/COLMAP installed, a second signal (the work
// did not stop) still removes the temporary before dying.
TEST_F(OutputFilesTest, SecondSignalUnderStopHandlersRemovesTheTemporary) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(fds[0]);
    InstallTempCleanupOnSignals();
    ScopedStopSignals stop;
    AtomicFile f(P("stuck.csv"));
    const std::string temp = f.temp_path() + "\n";
    if (::write(fds[1], temp.data(), temp.size()) < 0) ::_exit(3);
    while (!StopRequested()) ::usleep(1000);
    if (::write(fds[1], "s", 1) < 0) ::_exit(3);  // first signal seen; now "stuck"
    for (;;) ::pause();
  }
  ::close(fds[1]);
  std::string temp;
  char c;
  while (::read(fds[0], &c, 1) == 1 && c != '\n') temp += c;
  ASSERT_TRUE(fs::exists(temp));
  ::kill(child, SIGTERM);
  ASSERT_EQ(::read(fds[0], &c, 1), 1);
  EXPECT_TRUE(fs::exists(temp));  // the first signal only asks the work to stop
  ::kill(child, SIGTERM);
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(fds[0]);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_FALSE(fs::exists(temp));
}

}  // namespace
}  // namespace hapcine
