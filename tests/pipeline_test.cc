// End-to-end: the `hapcine` program as a user runs it, on a clip made on the
// spot: synth -> estimate -> eval -> haptics (+ .hjif) -> play on the
// simulated seat; and the bad inputs a user meets at each step (exit code 1,
// one line naming the file, no output left behind).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::LastLine;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

namespace {

// Files in `dir` whose name starts with `stem`, and output temporaries
// (".<pid>-<n>-<host>.hapcine-tmp", core/output_files.h).
int CountFilesStartingWith(const fs::path& dir, const std::string& stem) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(stem, 0) == 0 || name.find(".hapcine-tmp") != std::string::npos) ++n;
  }
  return n;
}

class PipelineTest : public ::testing::Test {
 protected:
  // One small clip for the whole suite: tilting (rotation about X only), so
  // the estimate must show rotation with no translation. 480x270 keeps the
  // render and the estimate to seconds.
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("hapcine_e2e_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    const RunResult r = RunHapcine("synth tilting --width 480 --height 270 --duration-s 3.5 -o " +
                                       Quote(dir_),
                                   dir_);
    synth_ok_ = r.exit_code == 0;
    if (!synth_ok_) std::fprintf(stderr, "synth failed: %s\n", r.err.c_str());
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void SetUp() override { ASSERT_TRUE(synth_ok_) << "the synthetic clip could not be rendered"; }

  static fs::path dir_;
  static bool synth_ok_;
};
fs::path PipelineTest::dir_;
bool PipelineTest::synth_ok_ = false;

TEST_F(PipelineTest, SynthEstimateEvalHapticsPlay) {
  const fs::path video = dir_ / "tilting.mp4";
  const fs::path gt = dir_ / "tilting.camera.csv";
  const fs::path est = dir_ / "tilting.est.camera.csv";
  ASSERT_TRUE(fs::exists(video));
  ASSERT_TRUE(fs::exists(gt));

  RunResult r = RunHapcine("estimate -q " + Quote(video) + " -o " + Quote(est), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const hapcine::CameraPath path = hapcine::ReadCameraPathFile(est.string());
  const hapcine::CameraPath truth = hapcine::ReadCameraPathFile(gt.string());
  ASSERT_EQ(path.frames.size(), truth.frames.size());
  // A tilt is a rotation: no frame may carry translation, and the model
  // column says which simpler model was chosen.
  for (const auto& f : path.frames) {
    EXPECT_EQ(f.center.norm(), 0.0) << "frame " << f.frame;
    ASSERT_TRUE(f.model.has_value());
    EXPECT_TRUE(*f.model == "static" || *f.model == "rotation" || *f.model == "rotation+zoom")
        << "frame " << f.frame << " model " << *f.model;
  }

  r = RunHapcine("eval --json --gt " + Quote(gt) + " --est " + Quote(est), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  const auto& overall = report.at("overall");
  // Loose bounds for a 480x270 clip; docs/estimate.md has the full-size figures.
  EXPECT_LT(overall.at("rotation_deg").at("mean").get<double>(), 0.3);
  EXPECT_LT(overall.at("zoom_ratio_percent").at("mean").get<double>(), 1.0);
  EXPECT_EQ(overall.at("frames").get<int>(), static_cast<int>(truth.frames.size()));

  const fs::path track = dir_ / "tilting.haptic.csv";
  const fs::path hjif = dir_ / "tilting.hjif";
  r = RunHapcine("haptics " + Quote(est) + " --model cinematic -o " + Quote(track) + " --hjif " +
                     Quote(hjif),
                 dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const hapcine::HapticTrack haptic = hapcine::ReadHapticTrackFile(track.string());
  EXPECT_EQ(haptic.model, "cinematic");
  ASSERT_FALSE(haptic.samples.empty());
  EXPECT_NEAR(haptic.duration_s(), truth.frames.back().time_s, 0.1);
  double max_abs = 0, max_motion = 0;
  for (const auto& s : haptic.samples)
    for (int a = 0; a < hapcine::kNumActuators; ++a) {
      max_abs = std::max(max_abs, s.pos_m[a].cwiseAbs().maxCoeff());
      max_motion = std::max(max_motion, s.pos_m[a].norm());
    }
  EXPECT_LE(max_abs, 0.05) << "an actuator left its 0.10 m workspace";
  EXPECT_GT(max_motion, 0.005) << "a tilt must move the seat";
  std::ifstream hj(hjif);
  const nlohmann::json hjif_doc = nlohmann::json::parse(hj);
  EXPECT_TRUE(hjif_doc.contains("perceptions"));

  // The film on the simulated seat, headless, with loop statistics.
  r = RunHapcine("play " + Quote(video) + " --track " + Quote(track) +
                     " --device sim --headless --no-realtime --stats --fault-log " +
                     Quote(dir_ / "fault.csv"),
                 dir_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE((r.out + r.err).find("p99"), std::string::npos) << r.out << r.err;

  // The same track as MPEG-I .hjif plays too, and eval compares with it.
  r = RunHapcine("play " + Quote(video) + " --track " + Quote(hjif) +
                     " --device sim --headless --no-realtime --stats",
                 dir_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = RunHapcine("eval --json --gt " + Quote(gt) + " --est " + Quote(est) + " --haptic-track " +
                     Quote(hjif),
                 dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out).at("haptic").at("samples").get<int>(), 1000);
  // A perception the HapSeat cannot play is refused with one line naming it.
  nlohmann::json vibration = hjif_doc;
  vibration["perceptions"][1]["perception_modality"] = "Vibrotactile";
  const fs::path vib = dir_ / "vibration.hjif";
  std::ofstream(vib) << vibration.dump();
  r = RunHapcine("play " + Quote(video) + " --track " + Quote(vib) + " --device sim --headless",
                 dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine play: " + vib.string() +
                       ": perception 1 (Vibrotactile): only Position perceptions can play on the "
                       "HapSeat\n");
}

// docs/batch.md: a local batch handles any file name. A newline, '=' and ','
// in the film's name go into the `# source=` headers of its camera path and
// haptic track, which must read back (escaped, core/header_value.h).
TEST_F(PipelineTest, BatchHandlesAFilmWithANewlineInItsName) {
  const fs::path lib = dir_ / "newline library";
  const fs::path out = dir_ / "newline out";
  fs::create_directories(lib);
  const std::string name = "two\nlines=1, film.mp4";
  fs::copy_file(dir_ / "tilting.mp4", lib / name, fs::copy_options::overwrite_existing);
  const RunResult r = RunHapcine("batch " + Quote(lib) + " -o " + Quote(out) +
                                     " --jobs 1 --models cinematic --progress lines"
                                     " --estimate-args --draft",
                                 dir_);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::vector<fs::path> paths, tracks;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const std::string f = e.path().filename().string();
    if (f.size() > 11 && f.compare(f.size() - 11, 11, ".camera.csv") == 0) paths.push_back(e);
    if (f.size() > 11 && f.compare(f.size() - 11, 11, ".haptic.csv") == 0) tracks.push_back(e);
  }
  ASSERT_EQ(paths.size(), 1u);
  ASSERT_EQ(tracks.size(), 1u);
  const hapcine::CameraPath path = hapcine::ReadCameraPathFile(paths[0].string());
  const std::string source = path.metadata.at("source");
  EXPECT_EQ(fs::path(source).filename().string(), name) << source;
  EXPECT_GT(path.frames.size(), 10u);
  const hapcine::HapticTrack track = hapcine::ReadHapticTrackFile(tracks[0].string());
  EXPECT_NE(track.source.find(".camera.csv"), std::string::npos) << track.source;
  EXPECT_FALSE(track.samples.empty());
}

// `estimate --report`: the per-window JSON (docs/formats.md "Estimate
// report"), on a travelling clip (general windows: candidate solves).
TEST_F(PipelineTest, EstimateReportListsEveryWindowsCandidatesModelAndSolve) {
  const fs::path dir = dir_ / "report";
  fs::create_directories(dir);
  RunResult r = RunHapcine("synth traveling --width 480 --height 270 --duration-s 2 -o " + Quote(dir), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path est = dir / "traveling.est.camera.csv", report_path = dir / "traveling.report.json";
  r = RunHapcine("estimate -q " + Quote(dir / "traveling.mp4") + " -o " + Quote(est) + " --window 24 --report " +
                     Quote(report_path),
                 dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The algorithms print nothing: with -q the only lines are the command's
  // own per-shot warnings, each naming the video.
  std::istringstream err_lines(r.err);
  for (std::string line; std::getline(err_lines, line);)
    EXPECT_EQ(line.rfind("hapcine estimate: " + (dir / "traveling.mp4").string() + ": ", 0), 0u) << line;
  EXPECT_EQ(CountFilesStartingWith(dir, "traveling.report.json"), 1);  // no temporary left
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report.at("format"), "hapcine-estimate-report");
  EXPECT_EQ(report.at("version"), 1);
  EXPECT_EQ(report.at("frames").get<size_t>(), hapcine::ReadCameraPathFile(est.string()).frames.size());
  std::vector<std::string> stages;
  for (const auto& s : report.at("stages")) {
    stages.push_back(s.at("name"));
    EXPECT_GE(s.at("wall_s").get<double>(), 0);
    EXPECT_GE(s.at("thread_cpu_s").get<double>(), 0);
  }
  EXPECT_NE(std::find(stages.begin(), stages.end(), "tracking done"), stages.end());
  EXPECT_EQ(stages.back(), "estimation done");
  const auto& windows = report.at("windows");
  ASSERT_GE(windows.size(), 2u);  // 2 s at --window 24
  int focal_candidates = 0, previous_last = -1;
  for (const auto& w : windows) {
    EXPECT_EQ(w.at("shot"), 0);
    EXPECT_GT(w.at("last_frame").get<int>(), previous_last);
    previous_last = w.at("last_frame");
    EXPECT_TRUE(w.at("model").is_string());
    EXPECT_GT(w.at("points").get<int>(), 0);
    EXPECT_GT(w.at("observations").get<int>(), 0);
    EXPECT_LT(w.at("rms_px").get<double>(), 2.0);
    const auto& ba = w.at("ba");
    EXPECT_TRUE(ba.at("success").get<bool>());
    EXPECT_GT(ba.at("iterations").get<int>(), 0);
    EXPECT_LE(ba.at("final_cost").get<double>(), ba.at("initial_cost").get<double>());
    EXPECT_FALSE(ba.at("termination").get<std::string>().empty());
    int interval_inliers = 0;
    for (const auto& k : w.at("keyframes")) {
      EXPECT_TRUE(k.at("model").is_string());
      if (k.contains("inliers")) {
        interval_inliers += k.at("inliers").get<int>();
        EXPECT_LE(k.at("inliers").get<int>(), k.at("correspondences").get<int>());
        EXPECT_TRUE(k.at("gric").contains("essential"));
      }
    }
    EXPECT_GT(interval_inliers, 0);
    for (const auto& c : w.at("candidates")) {
      EXPECT_TRUE(c.at("score").is_number());
      EXPECT_TRUE(c.at("chosen").is_boolean());
      if (c.at("test") == "focal") ++focal_candidates;
    }
    EXPECT_TRUE(w.at("timings_s").contains("constant_focal_solve"));
  }
  EXPECT_GT(focal_candidates, 0) << "a travelling window compares a per-keyframe focal";
  // The report changes nothing in the camera path.
  const fs::path plain = dir / "traveling.plain.camera.csv";
  r = RunHapcine("estimate -q " + Quote(dir / "traveling.mp4") + " -o " + Quote(plain) + " --window 24", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream a(est), b(plain);
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  EXPECT_EQ(sa.str(), sb.str());
}

TEST_F(PipelineTest, MoverPresetRendersAndEstimatesEndToEnd) {
  // A static camera on a turning head: the clip renders, the estimator runs through it, and
  // eval compares the two paths (accuracy on it is docs/generalisation.md's, not this test's).
  const fs::path dir = dir_ / "movers";
  fs::create_directories(dir);
  RunResult r = RunHapcine("synth head_turn --width 320 --height 180 --duration-s 1.5 -o " + Quote(dir), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path gt = dir / "head_turn.camera.csv", est = dir / "head_turn.est.camera.csv";
  EXPECT_EQ(hapcine::ReadCameraPathFile(gt.string()).metadata.at("movers"), "head");
  r = RunHapcine("estimate -q " + Quote(dir / "head_turn.mp4") + " -o " + Quote(est), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(hapcine::ReadCameraPathFile(est.string()).frames.size(), 36u);
  r = RunHapcine("eval --json --gt " + Quote(gt) + " --est " + Quote(est), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report.at("frames").at("matched").get<int>(), 36);
  EXPECT_TRUE(report.at("overall").at("gt_static").get<bool>());
}

TEST_F(PipelineTest, EstimateRejectsBadVideosWithOneLineAndNoOutput) {
  const fs::path empty = dir_ / "empty file.mp4";
  std::ofstream(empty).close();
  const fs::path text = dir_ / "notes.mp4";
  std::ofstream(text) << "this is not a video\n";
  const fs::path truncated = dir_ / "truncated.mp4";
  {
    std::ifstream in(dir_ / "tilting.mp4", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, 2000);
  }
  // Made from the clip with the ffmpeg CLI: audio only, one frame, and an MP4
  // with its index first cut at 60 % (decodable frames, then the end of the
  // file long before the declared length).
  const auto ffmpeg = [&](const std::string& args, const fs::path& out) {
    const std::string cmd =
        "ffmpeg -nostdin -hide_banner -loglevel error -y " + args + " " + Quote(out);
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return out;
  };
  const fs::path clip = dir_ / "tilting.mp4";
  const fs::path audio =
      ffmpeg("-f lavfi -i sine=frequency=440:duration=0.5 -c:a aac", dir_ / "tone.m4a");
  const fs::path single = ffmpeg("-i " + Quote(clip) + " -frames:v 1", dir_ / "one frame.mp4");
  const fs::path indexed =
      ffmpeg("-i " + Quote(clip) + " -c copy -movflags +faststart", dir_ / "indexed.mp4");
  const fs::path cut_short = dir_ / "cut short.mp4";
  fs::copy_file(indexed, cut_short, fs::copy_options::overwrite_existing);
  fs::resize_file(cut_short, fs::file_size(indexed) * 6 / 10);
  const std::map<fs::path, std::string> reasons = {
      {audio, "no video stream"}, {single, "at least two"}, {cut_short, "truncated"}};
  for (const fs::path& bad :
       {empty, text, truncated, dir_ / "missing.mp4", audio, single, cut_short}) {
    const fs::path out = dir_ / ("bad_" + bad.stem().string() + ".camera.csv");
    const RunResult r = RunHapcine("estimate -q " + Quote(bad) + " -o " + Quote(out), dir_);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(LastLine(r.err).find(bad.filename().string()), std::string::npos)
        << "the error must name the file: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    if (reasons.count(bad)) {
      EXPECT_NE(r.err.find(reasons.at(bad)), std::string::npos) << r.err;
    }
    EXPECT_EQ(CountFilesStartingWith(dir_, out.filename().string()), 0)
        << "output left behind for " << bad;
  }
}

TEST_F(PipelineTest, HapticsRejectsMalformedCameraPathWithLineNumber) {
  const fs::path bad = dir_ / "nan.camera.csv";
  {
    std::ifstream in(dir_ / "tilting.camera.csv");
    std::ofstream out(bad);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      if (n == 10) line = "8,0.3,0,0,0,1,0,0,0,nan";  // a NaN field of view on line 10
      out << line << "\n";
    }
  }
  const fs::path track = dir_ / "nan.haptic.csv";
  const RunResult r = RunHapcine("haptics " + Quote(bad) + " -o " + Quote(track), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("nan.camera.csv:10"), std::string::npos) << r.err;
  EXPECT_EQ(CountFilesStartingWith(dir_, "nan.haptic.csv"), 0);
}

TEST_F(PipelineTest, UsageErrorsExitTwo) {
  EXPECT_EQ(RunHapcine("estimate --no-such-flag x.mp4 -o y.csv", dir_).exit_code, 2);
  EXPECT_EQ(RunHapcine("no-such-command", dir_).exit_code, 2);
  const RunResult blur = RunHapcine("estimate --blur-noise -1 x.mp4 -o y.camera.csv", dir_);
  EXPECT_EQ(blur.exit_code, 2);
  EXPECT_NE(blur.err.find("--blur-noise: -1 is outside [0, 1]"), std::string::npos) << blur.err;
  EXPECT_EQ(CountFilesStartingWith(dir_, "y.camera.csv"), 0);
  // The lens: the pairs' measurement is the default and gives way to a known
  // k1 or the bundle's; asked for beside either, or those two together, it
  // is a contradiction.
  for (const char* lens : {"--lens-distortion --lens-k1 0.01", "--lens-distortion --lens-bundle",
                           "--lens-bundle --lens-k1 0.01"}) {
    const RunResult both =
        RunHapcine(std::string("estimate ") + lens + " x.mp4 -o y.camera.csv", dir_);
    EXPECT_EQ(both.exit_code, 2) << lens;
    EXPECT_NE(both.err.find("exclude each other"), std::string::npos) << both.err;
  }
  const RunResult help = RunHapcine("eval --help", dir_);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--gt"), std::string::npos);
}

}  // namespace
