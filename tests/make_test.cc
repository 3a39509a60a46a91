// End-to-end: `hapcine make` on a short synthetic clip: the first run writes
// the camera path and haptic track beside the film; a second run with
// another model reuses the camera path (no estimate); a changed estimate
// option estimates again; -o DIR puts everything there; a bad input is one
// line naming the file, exit 1, and leaves nothing behind.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::LastLine;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;
using hapcine_test::Slurp;

namespace {

// Names in `dir` (not recursive) other than the ones listed.
std::vector<std::string> OtherNames(const fs::path& dir, const std::vector<std::string>& known) {
  std::vector<std::string> other;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (std::find(known.begin(), known.end(), name) == known.end()) other.push_back(name);
  }
  return other;
}

class MakeTest : public ::testing::Test {
 protected:
  // One clip for the suite, copied into a folder of its own (synth writes
  // its ground truth as <preset>.camera.csv, the name make writes).
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("hapcine_make_" + std::to_string(getpid()));
    fs::create_directories(root_ / "render");
    const RunResult r = RunHapcine("synth tilting --width 192 --height 108 --duration-s 1.5 -o " +
                                       Quote(root_ / "render"),
                                   root_);
    synth_ok_ = r.exit_code == 0;
    if (!synth_ok_) std::fprintf(stderr, "synth failed: %s\n", r.err.c_str());
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  void SetUp() override {
    ASSERT_TRUE(synth_ok_) << "the synthetic clip could not be rendered";
    film_dir_ = root_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(film_dir_);
    fs::copy_file(root_ / "render" / "tilting.mp4", film_dir_ / "clip.mp4");
  }
  RunResult Make(const std::string& args) {
    return RunHapcine("make " + Quote(film_dir_ / "clip.mp4") + " " + args, film_dir_);
  }
  // The estimate step's log: rewritten only when the estimate runs.
  fs::file_time_type EstimateLogTime(const fs::path& out_dir) {
    for (const auto& e : fs::directory_iterator(out_dir / ".hapcine"))
      return fs::last_write_time(e.path() / "logs" / "estimate.log");
    return {};
  }

  static fs::path root_;
  static bool synth_ok_;
  fs::path film_dir_;
};

fs::path MakeTest::root_;
bool MakeTest::synth_ok_ = false;

TEST_F(MakeTest, ReusesTheCameraPathUntilTheFilmOrEstimateSettingsChange) {
  const RunResult first = Make("--draft");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const fs::path camera = film_dir_ / "clip.camera.csv", haptic = film_dir_ / "clip.haptic.csv";
  ASSERT_TRUE(fs::is_regular_file(camera));
  ASSERT_TRUE(fs::is_regular_file(haptic));
  EXPECT_NE(first.err.find("estimate            ran"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("shot 0 (frames 0-"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("camera path  " + camera.string()), std::string::npos) << first.err;
  EXPECT_NE(Slurp(haptic).find("model=cinematic"), std::string::npos);
  EXPECT_TRUE(OtherNames(film_dir_, {"clip.mp4", "clip.camera.csv", "clip.haptic.csv", ".hapcine",
                                     "stderr.txt"})
                  .empty());
  const std::string camera_bytes = Slurp(camera);
  const auto log_time = EstimateLogTime(film_dir_);

  // Another model and a haptics option: the camera path is reused.
  const RunResult second = Make("--draft --model semantic --washout-tau 3 --hjif");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("estimate            reused"), std::string::npos) << second.err;
  EXPECT_EQ(EstimateLogTime(film_dir_), log_time) << "the estimate ran again";
  EXPECT_EQ(Slurp(camera), camera_bytes);
  EXPECT_NE(Slurp(haptic).find("model=semantic"), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(film_dir_ / "clip.hjif"));

  // Back to the first model: its step ran before, but the file now holds
  // the semantic track, so it runs again (still no estimate).
  const RunResult third = Make("--draft");
  ASSERT_EQ(third.exit_code, 0) << third.err;
  EXPECT_NE(third.err.find("haptics-cinematic   ran"), std::string::npos) << third.err;
  EXPECT_NE(Slurp(haptic).find("model=cinematic"), std::string::npos);
  EXPECT_EQ(EstimateLogTime(film_dir_), log_time);

  // A changed estimate option: estimated again.
  const RunResult fourth = Make("--draft --tracks 150");
  ASSERT_EQ(fourth.exit_code, 0) << fourth.err;
  EXPECT_NE(fourth.err.find("estimate            ran"), std::string::npos) << fourth.err;
}

// The largest |value| of the actuator columns of a haptic track's rows.
double LargestDisplacement(const std::string& track) {
  std::istringstream in(track);
  double largest = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("time_s", 0) == 0) continue;
    std::istringstream row(line);
    std::string cell;
    std::getline(row, cell, ',');  // time_s
    for (int k = 0; k < 9 && std::getline(row, cell, ','); ++k)
      largest = std::max(largest, std::abs(std::stod(cell)));
  }
  return largest;
}

TEST_F(MakeTest, AnEditsFileReRendersTheHapticsButNeverReEstimates) {
  const RunResult first = Make("--draft --hjif");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const fs::path haptic = film_dir_ / "clip.haptic.csv", edits = film_dir_ / "clip.edits.json";
  const std::string plain = Slurp(haptic), plain_hjif = Slurp(film_dir_ / "clip.hjif");
  ASSERT_GT(LargestDisplacement(plain), 0.01);
  const auto log_time = EstimateLogTime(film_dir_);

  { std::ofstream(edits) << R"({"format": "hapcine-edits", "version": 1, "shots": [{"shot": 0, "gain": 0.5}]})"; }
  const RunResult edited = Make("--draft --hjif");
  ASSERT_EQ(edited.exit_code, 0) << edited.err;
  EXPECT_NE(edited.err.find("make: edits from " + edits.string()), std::string::npos) << edited.err;
  EXPECT_NE(edited.err.find("estimate            reused"), std::string::npos) << edited.err;
  EXPECT_NE(edited.err.find("haptics-cinematic   ran"), std::string::npos) << edited.err;
  EXPECT_EQ(EstimateLogTime(film_dir_), log_time) << "the estimate ran again";
  const std::string halved = Slurp(haptic);
  EXPECT_NE(halved.find("# edited_shots=0"), std::string::npos);
  EXPECT_NEAR(LargestDisplacement(halved), 0.5 * LargestDisplacement(plain), 2e-7);
  EXPECT_NE(Slurp(film_dir_ / "clip.hjif"), plain_hjif);  // made from the new track

  // Unchanged edits: nothing runs. A bad one: refused before any step, naming the field.
  EXPECT_NE(Make("--draft --hjif").err.find("every output up to date"), std::string::npos);
  { std::ofstream(edits) << R"({"format": "hapcine-edits", "version": 1, "shots": [{"shot": 0, "gain": 9}]})"; }
  const RunResult bad = Make("--draft --hjif");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(LastLine(bad.err),
            "hapcine make: " + edits.string() + ": shots[0].gain: must be in [0, 4]");
  EXPECT_EQ(Slurp(haptic), halved);

  // --no-edits: the plain track again, still without estimating.
  const RunResult ignored = Make("--draft --hjif --no-edits");
  ASSERT_EQ(ignored.exit_code, 0) << ignored.err;
  EXPECT_EQ(ignored.err.find("make: edits from"), std::string::npos) << ignored.err;
  EXPECT_EQ(Slurp(haptic), plain);
  EXPECT_EQ(EstimateLogTime(film_dir_), log_time);

  // `hapcine haptics --edits` says the same of a bad file, and makes the same track of a good one.
  const std::string haptics = "haptics " + Quote(film_dir_ / "clip.camera.csv") + " -o " +
                              Quote(film_dir_ / "direct.haptic.csv") + " --edits " + Quote(edits);
  const RunResult direct = RunHapcine(haptics, film_dir_);
  EXPECT_EQ(direct.exit_code, 1);
  EXPECT_EQ(LastLine(direct.err),
            "hapcine haptics: " + edits.string() + ": shots[0].gain: must be in [0, 4]");
  { std::ofstream(edits) << R"({"format": "hapcine-edits", "version": 1, "shots": [{"shot": 0, "gain": 0.5}]})"; }
  ASSERT_EQ(RunHapcine(haptics, film_dir_).exit_code, 0);
  EXPECT_EQ(Slurp(film_dir_ / "direct.haptic.csv"), halved);
}

// The summary names zoom-ambiguous shots, as batch's does: the camera path's
// header edited to say so (same size, so the film stays up to date and the
// summary reads the edited header).
TEST_F(MakeTest, SummaryNamesZoomAmbiguousShots) {
  const RunResult first = Make("--draft");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.err.find("zoom ambiguous"), std::string::npos) << first.err;
  const fs::path camera = film_dir_ / "clip.camera.csv";
  std::string text = Slurp(camera);
  const size_t at = text.find(" zoom_ambiguous:0 ");
  ASSERT_NE(at, std::string::npos) << text.substr(0, 2000);
  text.replace(at, 18, " zoom_ambiguous:9 ");
  // And as read as a still camera before a moving subject (a field of the
  // same length replaced: the file's size is part of what make reuses by).
  const size_t inliers = text.find(" inlier_ratio:0.");
  ASSERT_NE(inliers, std::string::npos);
  text.replace(inliers, 19, " still_border:1    ");
  { std::ofstream(camera, std::ios::binary) << text; }

  const RunResult second = Make("--draft");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("every output up to date"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find(" shot(s), 1 zoom ambiguous, model cinematic"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("frames lost, median confidence "), std::string::npos) << second.err;
  EXPECT_NE(second.err.find(", zoom ambiguous in 9 of "), std::string::npos) << second.err;
  EXPECT_NE(second.err.find(" frames, read as a still camera (its border stays still"), std::string::npos)
      << second.err;
}

TEST_F(MakeTest, OutputFolderHoldsEverything) {
  const fs::path out = film_dir_ / "out dir";
  const RunResult r = Make("--draft -o " + Quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out / "clip.camera.csv"));
  EXPECT_TRUE(fs::is_regular_file(out / "clip.haptic.csv"));
  EXPECT_TRUE(fs::is_directory(out / ".hapcine"));
  EXPECT_TRUE(OtherNames(film_dir_, {"clip.mp4", "out dir", "stderr.txt"}).empty());
  EXPECT_TRUE(OtherNames(out, {"clip.camera.csv", "clip.haptic.csv", ".hapcine"}).empty());
}

TEST_F(MakeTest, BadInputIsOneLineAndLeavesNothing) {
  // A bad option value is refused before any work, with estimate's own check.
  const RunResult range = Make("--tracks 1");
  EXPECT_EQ(range.exit_code, 2);
  EXPECT_NE(range.err.find("--tracks: 1 is outside [10, 100000]"), std::string::npos) << range.err;
  EXPECT_FALSE(fs::exists(film_dir_ / ".hapcine"));
  // --fps applies to image sequences only: a usage error for a video, one line.
  const RunResult fps = Make("--fps 25");
  EXPECT_EQ(fps.exit_code, 2) << fps.err;
  EXPECT_EQ(fps.err, "hapcine make: --fps is for image folders and patterns; a video's times come "
                     "from its timestamps\n");
  EXPECT_FALSE(fs::exists(film_dir_ / ".hapcine"));

  const fs::path bad = film_dir_ / "notes.mp4";
  { std::ofstream(bad) << "not a film\n"; }
  const RunResult r = RunHapcine("make " + Quote(bad), film_dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(LastLine(r.err).rfind("hapcine make: " + bad.string() + ": not a media file", 0), 0u)
      << r.err;
  EXPECT_FALSE(fs::exists(film_dir_ / "notes.camera.csv"));
  EXPECT_FALSE(fs::exists(film_dir_ / "notes.haptic.csv"));
  for (const auto& e : fs::recursive_directory_iterator(film_dir_))
    EXPECT_EQ(e.path().string().find("hapcine-tmp"), std::string::npos) << e.path();

  const RunResult missing = RunHapcine("make " + Quote(film_dir_ / "missing.mp4"), film_dir_);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(LastLine(missing.err), "hapcine make: " + (film_dir_ / "missing.mp4").string() + ": no such file");

}

}  // namespace
