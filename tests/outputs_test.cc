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

#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;
using hapcine_test::Slurp;

namespace {


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
    ok_ = RunHapcine("synth tilting --width 192 --height 108 --duration-s 1.5 -o " + Quote(dir_), dir_)
                  .exit_code == 0 &&
          RunHapcine("haptics " + Quote(dir_ / "tilting.camera.csv") + " -o " +
                      Quote(dir_ / "tilting.haptic.csv"),
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
    const RunResult r = RunHapcine(args, work_);
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
  ExpectUsage("estimate -q " + Quote(Video()) + " -o " + Quote(Video()), {Video().string()});
  ExpectUsage("haptics " + Quote(Camera()) + " -o " + Quote(Camera()), {Camera().string()});
  ExpectUsage("haptics " + Quote(Camera()) + " -o " + Quote(work_ / "hard.csv"), {"hard.csv"});
  ExpectUsage("haptics " + Quote(Video()) + " -o " + Quote(Video()), {Video().string()});
  ExpectUsage("preview " + Quote(Video()) + " -o " + Quote(Video()), {Video().string()});
  ExpectUsage("preview " + Quote(Video()) + " --track " + Quote(Track()) + " -o " + Quote(work_ / "soft.csv"),
              {"soft.csv", Track().string()});
  ExpectUsage("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(Camera()),
              {Camera().string()});
  ExpectUsage("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " --per-frame " +
                  Quote(work_ / "hard.csv"),
              {"hard.csv"});
  fs::copy_file(Track(), work_ / "t.svg");
  ExpectUsage("plot haptic " + Quote(work_ / "t.svg") + " --format svg -o " + Quote(work_ / "t"),
              {"t.svg"});
  ExpectUsage("convert " + Quote(Camera()) + " --to-tum " + Quote(Camera()), {Camera().string()});
  ExpectUsage("convert --from-tum " + Quote(Camera()) + " --fov 60 -o " + Quote(Camera()),
              {Camera().string()});
  ExpectUsage("play " + Quote(Video()) + " --track " + Quote(Track()) + " --device none --no-video " +
                  "--fault-log " + Quote(Track()),
              {Track().string()});
  ExpectUsage("study plan " + Quote(Video()) + " -o " + Quote(Video()), {Video().string()});
  fs::copy_file(Camera(), work_ / "r.json");
  ExpectUsage("study analyze " + Quote(work_ / "r.json") + " -o " + Quote(work_ / "r"), {"r.json"});
  ExpectUsage("batch " + Quote(work_ / "r.json") + " -o " + Quote(work_ / "r.json"), {"r.json"});
  EXPECT_EQ(Slurp(Video()), video);
  EXPECT_EQ(Slurp(Camera()), camera);
  EXPECT_EQ(Slurp(Track()), track);
}

TEST_F(OutputsTest, TwoOutputsOnOnePathAreRefused) {
  const fs::path out = work_ / "out";
  ExpectUsage("haptics " + Quote(Camera()) + " -o " + Quote(out) + " --hjif " + Quote(out), {"-o", "--hjif"});
  ExpectUsage("haptics " + Quote(Camera()) + " --effects-out " + Quote(out) + " -o " + Quote(work_ / "." / "out"),
              {"--effects-out", "-o"});
  ExpectUsage("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(out) +
                  " --per-frame " + Quote(out),
              {"-o", "--per-frame"});
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(OutputsTest, AFailingOutputLeavesNoneOfTheOthers) {
  fs::create_directories(work_ / "dir");
  // A directory as output: refused before any work, naming it; no z.csv.
  RunResult r = RunHapcine("haptics " + Quote(Camera()) + " -o " + Quote(work_ / "z.csv") + " --hjif " +
                      Quote(work_ / "dir"),
                  work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find((work_ / "dir").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "z.csv"));
  r = RunHapcine("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(work_ / "e.json") +
                  " --per-frame " + Quote(work_ / "dir"),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "e.json"));
  // A write that fails after the work (a /dev/full: no space left): the other
  // outputs, complete by then, are not committed either.
  const fs::path full = DevNullCopy("full", 7);
  if (full.empty()) GTEST_SKIP() << "making a device node needs root";
  r = RunHapcine("haptics " + Quote(Camera()) + " -o " + Quote(work_ / "z.csv") + " --hjif " + Quote(full),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "z.csv"));
  r = RunHapcine("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(work_ / "e.json") +
                  " --per-frame " + Quote(full),
              work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "e.json"));
}

TEST_F(OutputsTest, SymlinkOutputsReplaceTheirTargetAndStay) {
  fs::create_directories(work_ / "real");
  for (const char* name : {"est.csv", "h.csv", "e.json", "t.txt", "p.mp4", "f.png"}) {
    std::ofstream(work_ / "real" / name) << "old";
    fs::create_symlink(fs::path("real") / name, work_ / name);
  }
  EXPECT_EQ(RunHapcine("estimate -q " + Quote(Video()) + " -o " + Quote(work_ / "est.csv"), work_).exit_code, 0);
  EXPECT_EQ(RunHapcine("haptics " + Quote(Camera()) + " -o " + Quote(work_ / "h.csv"), work_).exit_code, 0);
  EXPECT_EQ(RunHapcine("eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " +
                        Quote(work_ / "e.json"),
                    work_)
                .exit_code,
            0);
  EXPECT_EQ(RunHapcine("convert " + Quote(Camera()) + " --to-tum " + Quote(work_ / "t.txt"), work_).exit_code,
            0);
  EXPECT_EQ(RunHapcine("preview " + Quote(Video()) + " --max-side 96 -o " + Quote(work_ / "p.mp4"), work_)
                .exit_code,
            0);
  EXPECT_EQ(RunHapcine("plot haptic " + Quote(Track()) + " --format png -o " + Quote(work_ / "f"), work_)
                .exit_code,
            0);
  for (const char* name : {"est.csv", "h.csv", "e.json", "t.txt", "p.mp4", "f.png"}) {
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
       {"estimate -q " + Quote(Video()) + " -o " + Quote(null),
        "haptics " + Quote(Camera()) + " -o " + Quote(null) + " --hjif " + Quote(null),
        "eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(null) +
            " --per-frame " + Quote(null),
        "convert " + Quote(Camera()) + " --to-tum " + Quote(null),
        "preview " + Quote(Video()) + " --max-side 96 -o " + Quote(null),
        "plot haptic " + Quote(Track()) + " --format png -o " + Quote(work_ / "null"),
        "plot haptic " + Quote(Track()) + " --format svg -o " + Quote(null)}) {
    const RunResult r = RunHapcine(args, work_);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    EXPECT_TRUE(IsCharDevice(null)) << args;
  }
  EXPECT_TRUE(IsCharDevice(png));
  EXPECT_FALSE(fs::exists(null.string() + ".svg"));  // the device, not a file beside it
}

TEST_F(OutputsTest, PlotPrefixMayCarryItsExtension) {
  const RunResult r = RunHapcine("plot haptic " + Quote(Track()) + " -o " + Quote(work_ / "fig.png"), work_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(work_ / "fig.png"));
  EXPECT_TRUE(fs::exists(work_ / "fig.svg"));
  EXPECT_FALSE(fs::exists(work_ / "fig.png.png"));
}

TEST_F(OutputsTest, LongOutputNamesAreWritten) {
  const std::string stem(240, 'x');
  const fs::path base = work_ / stem;
  for (const std::string& args :
       {"estimate -q " + Quote(Video()) + " -o " + Quote(base.string() + ".camera.csv"),
        "haptics " + Quote(Camera()) + " -o " + Quote(base.string() + ".haptic.c") + " --hjif " +
            Quote(base.string() + ".hjif"),
        "eval --gt " + Quote(Camera()) + " --est " + Quote(Camera()) + " -o " + Quote(base.string() + ".json"),
        "convert " + Quote(Camera()) + " --to-tum " + Quote(base.string() + ".tum.txt"),
        "plot haptic " + Quote(Track()) + " -o " + Quote(base)}) {
    const RunResult r = RunHapcine(args, work_);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  }
  for (const char* suffix :
       {".camera.csv", ".haptic.c", ".hjif", ".json", ".tum.txt", ".png", ".svg"})
    EXPECT_TRUE(fs::exists(base.string() + suffix)) << suffix;
}

// batch: a film whose stem is 240 bytes runs (its output names are cut to
// fit 255 bytes).
TEST_F(OutputsTest, BatchRunsAFilmWithA240ByteStem) {
  const fs::path lib = work_ / "lib";
  fs::create_directories(lib);
  const std::string stem(240, 'f');
  fs::copy_file(Video(), lib / (stem + ".mp4"));
  const RunResult r = RunHapcine("batch " + Quote(lib) + " -o " + Quote(work_ / "out") +
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
  const RunResult r = RunHapcine("synth tilting --width 64 --height 36 --duration-s 0.5 -o " + Quote(work_),
                        work_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tilting.mp4"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / "tilting.camera.csv"));
}

}  // namespace
