#include "batch/make.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "batch/content_hash.h"
#include "batch/fake_step_for_test.h"
#include "batch/job_progress.h"
#include "core/error.h"

namespace hapcine::batch {
namespace {
namespace fs = std::filesystem;

TEST(MakeTest, StepFailureReasonKeepsTheStepsOwnReason) {
  EXPECT_EQ(StepFailureReason("estimate: exit 1: hapcine estimate: /a/f.mp4: not a media file",
                              "/a/f.mp4"),
            "not a media file (estimate step)");
  // A signal says what happened: kept.
  EXPECT_EQ(StepFailureReason("haptics-semantic: killed by signal 9 (Killed)", "f.mp4"),
            "killed by signal 9 (Killed) (haptics-semantic step)");
  // A folder error has no step name in front.
  EXPECT_EQ(StepFailureReason("/ro/.hapcine/f-1: cannot create folder: Permission denied", "f.mp4"),
            "/ro/.hapcine/f-1: cannot create folder: Permission denied");
}

TEST(MakeTest, FpsAppliesToImageSequencesOnly) {
  MakeOptions opt;
  opt.film = "film.mp4";
  opt.estimate_args = {"--draft"};
  EXPECT_NO_THROW(CheckMakeOptions(opt));
  opt.estimate_args = {"--fps", "25"};
  EXPECT_THROW(CheckMakeOptions(opt), UsageError);
  opt.estimate_args = {"--fps=25"};
  EXPECT_THROW(CheckMakeOptions(opt), UsageError);
  // An option whose name starts like it is not it.
  opt.estimate_args = {"--fpsx"};
  EXPECT_NO_THROW(CheckMakeOptions(opt));
  opt.film = "plates/plate.%04d.png";
  opt.estimate_args = {"--fps", "25"};
  EXPECT_NO_THROW(CheckMakeOptions(opt));
}

TEST(MakeTest, LayoutBesideTheFilmOrInTheOutputFolder) {
  FilmPlan film;
  film.path = "/films/a b.mp4";
  film.id = "a b-12345678";
  film.stem = "a b";
  MakeOptions opt;
  FilmLayout l = MakeLayout(opt, film);
  EXPECT_EQ(l.output_dir, "/films");
  EXPECT_EQ(l.state_dir, "/films/.hapcine/a b-12345678");
  EXPECT_EQ(l.camera, "a b.camera.csv");
  ASSERT_EQ(l.models.size(), 1u);
  EXPECT_EQ(l.models[0].haptic, "a b.haptic.csv");
  EXPECT_EQ(l.models[0].hjif, "");
  EXPECT_EQ(MakeStepNames(l), (std::vector<std::string>{"estimate", "haptics-cinematic"}));
  opt.out_dir = "/out";
  opt.model = "semantic";
  opt.hjif = opt.preview = opt.plot = true;
  l = MakeLayout(opt, film);
  EXPECT_EQ(l.output_dir, "/out");
  EXPECT_EQ(l.models[0].hjif, "a b.hjif");
  EXPECT_EQ(MakeStepNames(l), (std::vector<std::string>{"estimate", "haptics-semantic", "preview",
                                                        "plot-camera", "plot-haptic"}));
}

TEST(MakeTest, EditsFileBesideTheOutputsThenBesideTheFilm) {
  testutil::TempDir dir("make_edits");
  const std::string films = dir.path() + "/films", out = dir.path() + "/out";
  FilmPlan film;
  film.path = films + "/clip.mp4";
  film.id = "clip-12345678";
  film.stem = "clip";
  MakeOptions opt;
  EXPECT_EQ(MakeLayout(opt, film).edits, "");
  testutil::WriteFile(films + "/clip.edits.json", "{}");
  FilmLayout l = MakeLayout(opt, film);
  EXPECT_EQ(l.edits, films + "/clip.edits.json");
  EXPECT_EQ(l.edits_hash, FullFileHash(films + "/clip.edits.json"));
  opt.out_dir = out;
  EXPECT_EQ(MakeLayout(opt, film).edits, films + "/clip.edits.json");
  testutil::WriteFile(out + "/clip.edits.json", "{ }");
  EXPECT_EQ(MakeLayout(opt, film).edits, out + "/clip.edits.json");
  opt.use_edits = false;
  EXPECT_EQ(MakeLayout(opt, film).edits, "");
  // An --edits FILE among the haptics options is the one used.
  opt.use_edits = true;
  opt.haptics_args = {"--edits", dir.path() + "/mine.json"};
  EXPECT_EQ(MakeLayout(opt, film).edits, "");
}

TEST(MakeTest, AnEditedFilmRedoesWhatReadsTheTrackAndNeverTheEstimate) {
  testutil::TempDir dir("make_edits_run");
  const std::string log = dir.path() + "/calls.log";
  MakeOptions opt;
  opt.film = dir.path() + "/clip.mp4";
  testutil::WriteFile(opt.film, "FAKEVIDEO clip\n");
  opt.step_exe = testutil::WriteFakeStep(dir.path(), log);
  opt.hjif = opt.preview = opt.plot = true;
  RunMake(opt, nullptr);
  const std::string track = dir.path() + "/clip.haptic.csv";
  const std::string plain = testutil::ReadAll(track);

  testutil::WriteFile(dir.path() + "/clip.edits.json", "{\"format\":\"hapcine-edits\",\"version\":1}");
  const MakeResult edited = RunMake(opt, nullptr);
  ASSERT_EQ(edited.outcome.status, FilmStatus::kDone);
  std::map<std::string, bool> reused;
  for (const StepRecord& s : edited.outcome.steps) reused[s.name] = s.reused;
  EXPECT_EQ(reused, (std::map<std::string, bool>{{"estimate", true},
                                                 {"haptics-cinematic", false},
                                                 {"preview", false},
                                                 {"plot-camera", true},
                                                 {"plot-haptic", false}}));
  EXPECT_EQ(testutil::LogLines(log, "estimate ").size(), 1u);
  const std::string with_edits = testutil::ReadAll(track);
  EXPECT_NE(with_edits, plain);
  EXPECT_NE(with_edits.find("edits:{\"format\""), std::string::npos);
  EXPECT_NE(testutil::ReadAll(dir.path() + "/clip.preview.mp4").find(with_edits), std::string::npos);
  EXPECT_NE(testutil::ReadAll(dir.path() + "/clip.haptic.png").find(with_edits), std::string::npos);
  EXPECT_EQ(RunMake(opt, nullptr).outcome.status, FilmStatus::kSkipped);
}

TEST(MakeTest, OutputsOnRequestChangeTheSettingsButNotABatchs) {
  BatchOptions batch;
  const std::string batch_hash = SettingsHash(batch);
  MakeOptions opt;
  BatchOptions a = MakeBatchOptions(opt);
  a.models = batch.models;
  a.hjif = true;
  EXPECT_EQ(SettingsHash(a), batch_hash);  // a batch's hash is what it was
  a.plot = true;
  EXPECT_NE(SettingsHash(a), batch_hash);
  // The estimate step does not depend on them: the camera path is reused.
  EXPECT_EQ(EstimateStepKey(a), EstimateStepKey(batch));
}

TEST(JobProgressTest, FractionOverWeightedSteps) {
  EXPECT_DOUBLE_EQ(JobFraction({1.0, 0.0, 1.0}, 0, 0.5), 0.25);
  EXPECT_DOUBLE_EQ(JobFraction({1.0, 0.0, 1.0}, 2, 0.5), 0.75);
  EXPECT_DOUBLE_EQ(JobFraction({1.0, 1.0}, 1, 7.0), 1.0);  // clamped
  EXPECT_DOUBLE_EQ(JobFraction({0.0, 0.0}, 1, 0.5), 0.0);  // everything reused
  EXPECT_DOUBLE_EQ(JobFraction({}, -1, 0.0), 0.0);
}

TEST(JobProgressTest, ReadsTheLastProgressLineOfALog) {
  const fs::path log = fs::temp_directory_path() / ("hapcine_job_" + std::to_string(getpid()) + ".log");
  double f = -1;
  EXPECT_FALSE(LastStepFraction(log.string(), &f));  // no log yet
  {
    std::ofstream(log) << "estimate: 10/100 frames, 5.0/s, ETA 18.0s\n"
                          "hapcine estimate: f.mp4: warning: 1/2 of something\n"
                          "estimate: 30/120 frames, 5.0/s, ETA 18.0s\n"
                          "a line without numbers\n";
  }
  ASSERT_TRUE(LastStepFraction(log.string(), &f));
  EXPECT_DOUBLE_EQ(f, 0.25);
  { std::ofstream(log) << "estimate: 5/0 frames\nnothing\n"; }  // no total: not a fraction
  EXPECT_FALSE(LastStepFraction(log.string(), &f));
  fs::remove(log);
}

}  // namespace
}  // namespace hapcine::batch
