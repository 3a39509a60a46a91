// End-to-end: every command of the `hapcine` program writes its outputs
// through one helper (core/output_files.h). Each command is run through the
// cases that lost data before: an output that is an input (exit 2, input
// intact), two outputs on one path (exit 2), a failing second output (no
// first output left), a symlink output (its target replaced, the link kept),
// a copy of /dev/null as output (written directly, stays a device), a
// 250-byte output name, and no temporary left in any case.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct CommandRun {
  int exit_code = -1;
  std::string err;
};

CommandRun Hapcine(const std::string& args, const fs::path& dir) {
  const fs::path err_file = dir / "stderr.txt";
  const std::string cmd = std::string("'") + HAPCINE_EXE + "' " + args + " >/dev/null 2>'" +
                          err_file.string() + "'";
  const int status = std::system(cmd.c_str());
  CommandRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  return r;
}

std::string Q(const fs::path& p) { return "'" + p.string() + "'"; }

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Temporaries of the output helper, or of earlier versions, under dir.
std::vector<std::string> Temps(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".hapcine-tmp") != std::string::npos || name.find(".tmp-") != std::string::npos)
      found.push_back(e.path().string());
  }
  return found;
}

bool IsCharDevice(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

class OutputsTest : public ::testing::Test {
 protected:
  // One tiny clip, its ground-truth camera path and a haptic track, shared.
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("hapcine_outputs_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    ok_ = Hapcine("synth tilting --width 192 --height 108 --duration-s 1.5 -o " + Q(dir_), dir_)
                  .exit_code == 0 &&
          Hapcine("haptics " + Q(dir_ / "tilting.camera.csv") + " -o " +
                      Q(dir_ / "tilting.haptic.csv"),
                  dir_)
                  .exit_code == 0;
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void SetUp() override {
    ASSERT_TRUE(ok_) << "the shared clip could not be made";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = dir_ / info->name();
    fs::create_directories(work_);
  }
  void TearDown() override {
    EXPECT_TRUE(Temps(dir_).empty()) << Temps(dir_).front();
  }
  // Runs a command that must be refused as usage (exit 2) naming `names`.
  void ExpectUsage(const std::string& args, const std::vector<std::string>& names) {
    const CommandRun r = Hapcine(args, work_);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    for (const std::string& n : names) EXPECT_NE(r.err.find(n), std::string::npos) << r.err;
  }
  fs::path Video() const { return dir_ / "tilting.mp4"; }
  fs::path Camera() const { return dir_ / "tilting.camera.csv"; }
  fs::path Track() const { return dir_ / "tilting.haptic.csv"; }
  // A copy of /dev/null (or, minor 7, /dev/full) in the work folder (needs
  // root), else empty: a regression then replaces the copy, not the system's.
  fs::path DevNullCopy(const std::string& name = "null", unsigned minor = 3) const {
    const fs::path p = work_ / name;
    if (::geteuid() != 0 || ::mknod(p.c_str(), S_IFCHR | 0666, makedev(1, minor)) != 0) return {};
    return p;
  }

  static fs::path dir_;
  static bool ok_;
  fs::path work_;
};
fs::path OutputsTest::dir_;
bool OutputsTest::ok_ = false;

TEST_F(OutputsTest, OutputThatIsAnInputIsRefusedAndTheInputKept) {
  const std::string video = Slurp(Video()), camera = Slurp(Camera()), track = Slurp(Track());
  fs::create_hard_link(Camera(), work_ / "hard.csv");
  fs::create_symlink(Track(), work_ / "soft.csv");
  ExpectUsage("estimate -q " + Q(Video()) + " -o " + Q(Video()), {Video().string()});
  ExpectUsage("haptics " + Q(Camera()) + " -o " + Q(Camera()), {Camera().string()});
  ExpectUsage("haptics " + Q(Camera()) + " -o " + Q(work_ / "hard.csv"), {"hard.csv"});
  ExpectUsage("haptics " + Q(Video()) + " -o " + Q(Video()), {Video().string()});
  ExpectUsage("preview " + Q(Video()) + " -o " + Q(Video()), {Video().string()});
  ExpectUsage("preview " + Q(Video()) + " --track " + Q(Track()) + " -o " + Q(work_ / "soft.csv"),
              {"soft.csv", Track().string()});
  ExpectUsage("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(Camera()),
              {Camera().string()});
  ExpectUsage("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " --per-frame " +
                  Q(work_ / "hard.csv"),
              {"hard.csv"});
  fs::copy_file(Track(), work_ / "t.svg");
  ExpectUsage("plot haptic " + Q(work_ / "t.svg") + " --format svg -o " + Q(work_ / "t"),
              {"t.svg"});
  ExpectUsage("convert " + Q(Camera()) + " --to-tum " + Q(Camera()), {Camera().string()});
  ExpectUsage("convert --from-tum " + Q(Camera()) + " --fov 60 -o " + Q(Camera()),
              {Camera().string()});
  ExpectUsage("play " + Q(Video()) + " --track " + Q(Track()) + " --device none --no-video " +
                  "--fault-log " + Q(Track()),
              {Track().string()});
  ExpectUsage("study plan " + Q(Video()) + " -o " + Q(Video()), {Video().string()});
  fs::copy_file(Camera(), work_ / "r.json");
  ExpectUsage("study analyze " + Q(work_ / "r.json") + " -o " + Q(work_ / "r"), {"r.json"});
  ExpectUsage("batch " + Q(work_ / "r.json") + " -o " + Q(work_ / "r.json"), {"r.json"});
  EXPECT_EQ(Slurp(Video()), video);
  EXPECT_EQ(Slurp(Camera()), camera);
  EXPECT_EQ(Slurp(Track()), track);
}

TEST_F(OutputsTest, TwoOutputsOnOnePathAreRefused) {
  const fs::path out = work_ / "out";
  ExpectUsage("haptics " + Q(Camera()) + " -o " + Q(out) + " --hjif " + Q(out), {"-o", "--hjif"});
  ExpectUsage("haptics " + Q(Camera()) + " --effects-out " + Q(out) + " -o " + Q(work_ / "." / "out"),
              {"--effects-out", "-o"});
  ExpectUsage("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(out) +
                  " --per-frame " + Q(out),
              {"-o", "--per-frame"});
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(OutputsTest, AFailingOutputLeavesNoneOfTheOthers) {
  fs::create_directories(work_ / "dir");
  // A directory as output: refused before any work, naming it; no z.csv.
  CommandRun r = Hapcine("haptics " + Q(Camera()) + " -o " + Q(work_ / "z.csv") + " --hjif " +
                      Q(work_ / "dir"),
                  work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find((work_ / "dir").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "z.csv"));
  r = Hapcine("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(work_ / "e.json") +
                  " --per-frame " + Q(work_ / "dir"),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "e.json"));
  // A write that fails after the work (a /dev/full: no space left): the other
  // outputs, complete by then, are not committed either.
  const fs::path full = DevNullCopy("full", 7);
  if (full.empty()) GTEST_SKIP() << "making a device node needs root";
  r = Hapcine("haptics " + Q(Camera()) + " -o " + Q(work_ / "z.csv") + " --hjif " + Q(full),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "z.csv"));
  r = Hapcine("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(work_ / "e.json") +
                  " --per-frame " + Q(full),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "e.json"));
}

TEST_F(OutputsTest, SymlinkOutputsReplaceTheirTargetAndStay) {
  fs::create_directories(work_ / "real");
  for (const std::string& name : {"est.csv", "h.csv", "e.json", "t.txt", "p.mp4", "f.png"}) {
    std::ofstream(work_ / "real" / name) << "old";
    fs::create_symlink(fs::path("real") / name, work_ / name);
  }
  EXPECT_EQ(Hapcine("estimate -q " + Q(Video()) + " -o " + Q(work_ / "est.csv"), work_).exit_code, 0);
  EXPECT_EQ(Hapcine("haptics " + Q(Camera()) + " -o " + Q(work_ / "h.csv"), work_).exit_code, 0);
  EXPECT_EQ(Hapcine("eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " +
                        Q(work_ / "e.json"),
                    work_)
                .exit_code,
            0);
  EXPECT_EQ(Hapcine("convert " + Q(Camera()) + " --to-tum " + Q(work_ / "t.txt"), work_).exit_code,
            0);
  EXPECT_EQ(Hapcine("preview " + Q(Video()) + " --max-side 96 -o " + Q(work_ / "p.mp4"), work_)
                .exit_code,
            0);
  EXPECT_EQ(Hapcine("plot haptic " + Q(Track()) + " --format png -o " + Q(work_ / "f"), work_)
                .exit_code,
            0);
  for (const std::string& name : {"est.csv", "h.csv", "e.json", "t.txt", "p.mp4", "f.png"}) {
    EXPECT_TRUE(fs::is_symlink(work_ / name)) << name;
    EXPECT_NE(Slurp(work_ / "real" / name), "old") << name;
  }
}

TEST_F(OutputsTest, DeviceOutputsAreWrittenDirectly) {
  const fs::path null = DevNullCopy();
  if (null.empty()) GTEST_SKIP() << "making a device node needs root";
  const fs::path png = DevNullCopy("null.png");
  ASSERT_FALSE(png.empty());
  for (const std::string& args :
       {"estimate -q " + Q(Video()) + " -o " + Q(null),
        "haptics " + Q(Camera()) + " -o " + Q(null) + " --hjif " + Q(null),
        "eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(null) +
            " --per-frame " + Q(null),
        "convert " + Q(Camera()) + " --to-tum " + Q(null),
        "preview " + Q(Video()) + " --max-side 96 -o " + Q(null),
        "plot haptic " + Q(Track()) + " --format png -o " + Q(work_ / "null"),
        "plot haptic " + Q(Track()) + " --format svg -o " + Q(null)}) {
    const CommandRun r = Hapcine(args, work_);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    EXPECT_TRUE(IsCharDevice(null)) << args;
  }
  EXPECT_TRUE(IsCharDevice(png));
  EXPECT_FALSE(fs::exists(null.string() + ".svg"));  // the device, not a file beside it
}

TEST_F(OutputsTest, PlotPrefixMayCarryItsExtension) {
  const CommandRun r = Hapcine("plot haptic " + Q(Track()) + " -o " + Q(work_ / "fig.png"), work_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(work_ / "fig.png"));
  EXPECT_TRUE(fs::exists(work_ / "fig.svg"));
  EXPECT_FALSE(fs::exists(work_ / "fig.png.png"));
}

TEST_F(OutputsTest, LongOutputNamesAreWritten) {
  const std::string stem(240, 'x');
  const fs::path base = work_ / stem;
  for (const std::string& args :
       {"estimate -q " + Q(Video()) + " -o " + Q(base.string() + ".camera.csv"),
        "haptics " + Q(Camera()) + " -o " + Q(base.string() + ".haptic.c") + " --hjif " +
            Q(base.string() + ".hjif"),
        "eval --gt " + Q(Camera()) + " --est " + Q(Camera()) + " -o " + Q(base.string() + ".json"),
        "convert " + Q(Camera()) + " --to-tum " + Q(base.string() + ".tum.txt"),
        "plot haptic " + Q(Track()) + " -o " + Q(base)}) {
    const CommandRun r = Hapcine(args, work_);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  }
  for (const std::string& suffix : {".camera.csv", ".haptic.c", ".hjif", ".json", ".tum.txt",
                                    ".png", ".svg"})
    EXPECT_TRUE(fs::exists(base.string() + suffix)) << suffix;
}

// batch: a film whose stem is 240 bytes runs (its output names are cut to
// fit 255 bytes).
TEST_F(OutputsTest, BatchRunsAFilmWithA240ByteStem) {
  const fs::path lib = work_ / "lib";
  fs::create_directories(lib);
  const std::string stem(240, 'f');
  fs::copy_file(Video(), lib / (stem + ".mp4"));
  const CommandRun r = Hapcine("batch " + Q(lib) + " -o " + Q(work_ / "out") +
                            " --models cinematic --jobs 1 --progress quiet",
                        work_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  int tracks = 0;
  for (const auto& e : fs::recursive_directory_iterator(work_ / "out")) {
    const std::string name = e.path().filename().string();
    tracks += name.size() > 20 && name.compare(name.size() - 11, 11, ".haptic.csv") == 0;
  }
  EXPECT_EQ(tracks, 1);
}

// synth: a directory in the way of a clip is an error before any rendering.
TEST_F(OutputsTest, SynthRefusesADirectoryInTheWay) {
  fs::create_directories(work_ / "tilting.mp4");
  const CommandRun r = Hapcine("synth tilting --width 64 --height 36 --duration-s 0.5 -o " + Q(work_),
                        work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tilting.mp4"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "tilting.camera.csv"));
}

}  // namespace
