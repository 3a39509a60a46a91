#include "batch/batch.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "batch/content_hash.h"
#include "batch/fake_step_for_test.h"
#include "batch/library.h"
#include "batch/state_files.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/output_files.h"

namespace hapcine::batch {
namespace {
namespace fs = std::filesystem;

using testutil::LogLines;
using testutil::MakeTestLibrary;
using testutil::OutputFiles;
using testutil::ReadAll;
using testutil::TempDir;
using testutil::TempLeftovers;
using testutil::TestLibrary;
using testutil::WriteFakeStep;
using testutil::WriteFile;

const FilmOutcome* Find(const BatchSummary& s, const std::string& name) {
  for (const FilmOutcome& f : s.films) {
    if (fs::path(f.path).filename() == fs::path(name).filename() && f.path.size() >= name.size() &&
        f.path.compare(f.path.size() - name.size(), name.size(), name) == 0) {
      return &f;
    }
  }
  return nullptr;
}

class BatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lib_ = MakeTestLibrary(dir_.path() + "/library");
    log_ = dir_.path() + "/calls.log";
    options_.library = lib_.root;
    options_.out_dir = dir_.path() + "/out";
    options_.jobs = 3;
    options_.models = {"cinematic", "semantic"};
    options_.step_exe = WriteFakeStep(dir_.path(), log_);
    options_.progress = BatchOptions::Progress::kQuiet;
  }
  std::string FilmDir(const std::string& name) const {
    return options_.out_dir + "/" + FilmId(lib_.root + "/" + name);
  }

  TempDir dir_;
  TestLibrary lib_;
  std::string log_;
  BatchOptions options_;
};

TEST_F(BatchTest, FirstRunDoesGoodFilmsRecordsFailuresAndDuplicates) {
  const BatchSummary s = RunLocalBatch(options_);
  ASSERT_EQ(static_cast<int>(s.films.size()), lib_.total());
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);
  EXPECT_EQ(s.Count(FilmStatus::kFailed), 3);
  EXPECT_EQ(s.Count(FilmStatus::kDuplicate), 1);
  EXPECT_EQ(s.ExitCode(), 1);  // failures make the batch fail, after doing everything else

  for (const std::string& name : lib_.good) {
    const std::string dir = FilmDir(name);
    const std::string stem = FileStem(name);
    EXPECT_TRUE(fs::is_regular_file(dir + "/" + stem + ".camera.csv")) << dir;
    for (const char* m : {"cinematic", "semantic"}) {
      EXPECT_TRUE(fs::is_regular_file(dir + "/" + stem + "." + m + ".haptic.csv")) << dir;
      EXPECT_TRUE(fs::is_regular_file(dir + "/" + stem + "." + m + ".hjif")) << dir;
    }
    const auto done = ReadJsonFile(dir + "/done.json");
    ASSERT_TRUE(done.has_value()) << dir;
    EXPECT_EQ((*done)["outputs"].size(), 5u);
    EXPECT_EQ((*done)["path"], lib_.root + "/" + name);
    EXPECT_EQ((*done)["steps"].size(), 3u);
  }
  // Each failure has its one-line reason, from the step's stderr or the pre-check.
  EXPECT_NE(Find(s, "corrupt.mp4")->reason.find("estimate: exit 1: hapcine estimate: "),
            std::string::npos);
  EXPECT_NE(Find(s, "corrupt.mp4")->reason.find("corrupt video stream"), std::string::npos);
  EXPECT_NE(Find(s, "empty.mp4")->reason.find("empty file (0 bytes)"), std::string::npos);
  EXPECT_NE(Find(s, "notes.mp4")->reason.find("no video stream found"), std::string::npos);
  const auto failed = ReadJsonFile(FilmDir("corrupt.mp4") + "/failed.json");
  ASSERT_TRUE(failed.has_value());
  EXPECT_EQ((*failed)["step"], "estimate");
  EXPECT_FALSE(fs::exists(FilmDir("corrupt.mp4") + "/done.json"));

  const FilmOutcome* dup = Find(s, lib_.duplicate);
  ASSERT_NE(dup, nullptr);
  EXPECT_EQ(dup->status, FilmStatus::kDuplicate);
  EXPECT_EQ(dup->duplicate_of, FilmId(lib_.root + "/a.mp4"));
  EXPECT_TRUE(OutputFiles(FilmDir(lib_.duplicate)).empty());  // processed once, at a.mp4

  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);  // once per distinct good film
  EXPECT_TRUE(TempLeftovers(options_.out_dir).empty());

  const auto summary = ReadJsonFile(options_.out_dir + "/summary.json");
  ASSERT_TRUE(summary.has_value());
  EXPECT_EQ((*summary)["counts"]["done"], 5);
  EXPECT_EQ((*summary)["counts"]["failed"], 3);
  EXPECT_EQ((*summary)["counts"]["duplicate"], 1);
  const std::string text = ReadAll(options_.out_dir + "/summary.txt");
  EXPECT_NE(text.find("9 films: 5 done, 0 skipped (up to date), 3 failed, 1 duplicate"),
            std::string::npos)
      << text;
  // Timings by step: estimate ran for the 5 good films and the 2 that failed
  // in it (not the empty file, failed before any step); haptics for the 5.
  EXPECT_NE(text.find("steps run: estimate 7x, "), std::string::npos) << text;
  EXPECT_NE(text.find("; haptics-cinematic 5x, "), std::string::npos) << text;
}

TEST_F(BatchTest, RerunSkipsWhatIsDoneAndRetriesFailures) {
  RunLocalBatch(options_);
  const auto before = OutputFiles(options_.out_dir);
  const BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kSkipped), 5);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 0);
  EXPECT_EQ(s.Count(FilmStatus::kFailed), 3);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);  // nothing re-estimated
  EXPECT_EQ(OutputFiles(options_.out_dir), before);
}

TEST_F(BatchTest, ChangedContentRedoesOnlyThatFilm) {
  RunLocalBatch(options_);
  // Same size, same name, different bytes: caught by the content hash.
  const std::string b = lib_.root + "/b.mov";
  std::string content = ReadAll(b);
  content[content.size() - 2] ^= 1;
  WriteFile(b, content);
  const BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(Find(s, "b.mov")->status, FilmStatus::kDone);
  EXPECT_EQ(s.Count(FilmStatus::kSkipped), 4);
  EXPECT_EQ(LogLines(log_, "estimate " + b).size(), 2u);
}

TEST_F(BatchTest, ChangedSettingsRedoOnlyTheStepsTheyAffect) {
  RunLocalBatch(options_);
  options_.models = {"cinematic", "semantic", "random"};
  BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);  // camera paths reused
  EXPECT_EQ(LogLines(log_, "haptics random ").size(), 5u);
  EXPECT_EQ(LogLines(log_, "haptics cinematic ").size(), 5u);  // not redone either
  const FilmOutcome* a = Find(s, "a.mp4");
  ASSERT_EQ(a->steps.size(), 4u);
  EXPECT_TRUE(a->steps[0].reused);
  EXPECT_FALSE(a->steps[3].reused);

  options_.estimate_args = {"--max-frames", "100"};
  s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 10u);  // estimate args change everything
  EXPECT_NE(ReadAll(FilmDir("a.mp4") + "/a.camera.csv").find("args:--max-frames 100"),
            std::string::npos);

  options_.force = true;
  s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 15u);
}

TEST_F(BatchTest, EditingAFileNamedInStepArgumentsRedoesTheStepsThatReadIt) {
  const std::string seat = dir_.path() + "/seat.json";
  WriteFile(seat, "{\"k\": 1}\n");
  options_.haptics_args = {"--seat", seat, "--keyframes=" + seat};
  RunLocalBatch(options_);
  BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kSkipped), 5);  // same file, same content: up to date

  WriteFile(seat, "{\"k\": 2}\n");  // same name, same size, new content
  s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);  // the camera paths do not read it
  EXPECT_EQ(LogLines(log_, "haptics cinematic ").size(), 10u);
  const auto done = ReadJsonFile(FilmDir("a.mp4") + "/done.json");
  ASSERT_TRUE(done.has_value());
  EXPECT_EQ((*done)["settings"]["haptics_arg_files"][seat], FullFileHash(seat));
  EXPECT_TRUE((*done)["settings"]["haptics_arg_files"].contains("--keyframes=" + seat));
}

TEST_F(BatchTest, AnEditsFileBesideAFilmRedoesOnlyItsHaptics) {
  RunLocalBatch(options_);
  const std::string edits = lib_.root + "/a.edits.json";
  WriteFile(edits, "{\"format\":\"hapcine-edits\",\"version\":1}\n");
  BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 1);
  EXPECT_EQ(s.Count(FilmStatus::kSkipped), 4);
  const FilmOutcome* a = Find(s, "a.mp4");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->edits, edits);
  ASSERT_EQ(a->steps.size(), 3u);
  EXPECT_TRUE(a->steps[0].reused);   // estimate
  EXPECT_FALSE(a->steps[1].reused);  // haptics-cinematic
  EXPECT_FALSE(a->steps[2].reused);  // haptics-semantic
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);  // never estimated again
  const std::string track = ReadAll(FilmDir("a.mp4") + "/a.cinematic.haptic.csv");
  EXPECT_NE(track.find("edits:{\"format\""), std::string::npos) << track;
  EXPECT_NE(ReadAll(options_.out_dir + "/summary.txt").find("edits " + edits), std::string::npos);
  EXPECT_EQ((*ReadJsonFile(FilmDir("a.mp4") + "/done.json"))["edits_hash"], FullFileHash(edits));

  // Unchanged: up to date. Changed bytes: redone. In the output folder: that one wins.
  EXPECT_EQ(RunLocalBatch(options_).Count(FilmStatus::kSkipped), 5);
  WriteFile(edits, "{\"format\":\"hapcine-edits\",\"version\":1,\"revision\":1}\n");
  EXPECT_EQ(RunLocalBatch(options_).Count(FilmStatus::kDone), 1);
  const std::string beside_outputs = FilmDir("a.mp4") + "/a.edits.json";
  WriteFile(beside_outputs, "{\"format\":\"hapcine-edits\",\"version\":1,\"revision\":2}\n");
  s = RunLocalBatch(options_);
  EXPECT_EQ(Find(s, "a.mp4")->edits, beside_outputs);
  EXPECT_NE(ReadAll(FilmDir("a.mp4") + "/a.cinematic.haptic.csv").find("\"revision\":2"),
            std::string::npos);

  // --no-edits: the plain tracks again, still no estimate.
  options_.use_edits = false;
  s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 1);
  EXPECT_EQ(Find(s, "a.mp4")->edits, "");
  EXPECT_EQ(ReadAll(FilmDir("a.mp4") + "/a.cinematic.haptic.csv").find("edits:"), std::string::npos);
  EXPECT_EQ(LogLines(log_, "estimate ").size(), 5u);
  EXPECT_EQ(RunLocalBatch(options_).Count(FilmStatus::kSkipped), 5);
}

TEST(BatchOptionsTest, ArgumentFileHashesSeeOnlyExistingFiles) {
  TempDir dir("batch_argfiles");
  const std::string f = dir.path() + "/k.csv";
  WriteFile(f, "0,1,zoom,1\n");
  const auto h = ArgumentFileHashes({"--keyframes", f, "--rate=100", "--x=" + f, "--no-washout",
                                     dir.path(), dir.path() + "/missing.csv"});
  EXPECT_EQ(h.size(), 2u);  // f and --x=f; not the folder, the missing file or the numbers
  EXPECT_EQ(h[f], FullFileHash(f));
  EXPECT_EQ(h["--x=" + f], FullFileHash(f));
  BatchOptions a;
  EXPECT_TRUE(ArgumentFileHashes(a.haptics_args).empty());
  EXPECT_FALSE(SettingsJson(a).contains("haptics_arg_files"));  // old hashes unchanged
}

TEST_F(BatchTest, CrashingSilentAndMissingStepProgramsAreRecordedNotFatal) {
  WriteFile(lib_.root + "/crash.mp4", "FAKEVIDEO segv\n");
  WriteFile(lib_.root + "/silent.mp4", "FAKEVIDEO silent\n");
  BatchSummary s = RunLocalBatch(options_);
  EXPECT_NE(Find(s, "crash.mp4")->reason.find("killed by signal 11"), std::string::npos)
      << Find(s, "crash.mp4")->reason;
  EXPECT_NE(Find(s, "silent.mp4")->reason.find("exited 0 but did not write silent.camera.csv"),
            std::string::npos);
  EXPECT_EQ(s.Count(FilmStatus::kDone), 5);

  options_.step_exe = dir_.path() + "/no-such-program";
  options_.force = true;
  s = RunLocalBatch(options_);
  EXPECT_EQ(s.Count(FilmStatus::kFailed), 10);
  EXPECT_NE(Find(s, "a.mp4")->reason.find("exit 127: cannot execute step program"),
            std::string::npos)
      << Find(s, "a.mp4")->reason;
  // A failed redo leaves no done.json claiming the film is finished.
  EXPECT_FALSE(fs::exists(FilmDir("a.mp4") + "/done.json"));
}

TEST_F(BatchTest, StaleTemporariesAreCleanedAndLockedFilmsLeftAlone) {
  RunLocalBatch(options_);
  const std::string a = FilmDir("a.mp4");
  WriteFile(a + "/.tmp/a.camera.csv", "half");
  WriteFile(a + "/done.json.tmp-999999", "{");
  WriteFile(a + "/.steps/estimate.json.tmp-999999", "{");
  WriteFile(options_.out_dir + "/summary.json.tmp-999999", "{");
  // Temporaries of the output helper: any in a film folder, dead ones at the top.
  WriteFile(a + "/.1-0-00000000.hapcine-tmp", "{");
  long pid = 0;
  bool here = false;
  {
    AtomicFile probe(options_.out_dir + "/probe.txt");  // a name of this host's pattern
    ASSERT_TRUE(ParseTempName(fs::path(probe.temp_path()).filename().string(), &pid, &here));
    const std::string name = fs::path(probe.temp_path()).filename().string();
    const std::string dead = ".999999" + name.substr(name.find('-'));
    WriteFile(options_.out_dir + "/" + dead, "{");
  }
  {
    FilmLock held(FilmDir("b.mov"));  // as if another batch were working on it
    ASSERT_TRUE(held.locked());
    EXPECT_TRUE(FilmIsLocked(FilmDir("b.mov")));
    const BatchSummary s = RunLocalBatch(options_);
    EXPECT_EQ(Find(s, "b.mov")->status, FilmStatus::kBusy);
    EXPECT_EQ(Find(s, "a.mp4")->status, FilmStatus::kSkipped);
    EXPECT_EQ(s.ExitCode(), 1);
    EXPECT_EQ(ReadBatchStatus(options_.out_dir).running, 1);
  }
  EXPECT_FALSE(FilmIsLocked(FilmDir("b.mov")));
  EXPECT_TRUE(TempLeftovers(options_.out_dir).empty());
}

TEST_F(BatchTest, StatusCountsFromStateFiles) {
  EXPECT_THROW(ReadBatchStatus(options_.out_dir), Error);
  RunLocalBatch(options_);
  BatchStatus st = ReadBatchStatus(options_.out_dir);
  EXPECT_EQ(st.total, 9);
  EXPECT_EQ(st.done, 5);
  EXPECT_EQ(st.failed, 3);
  EXPECT_EQ(st.duplicate, 1);
  EXPECT_EQ(st.pending, 0);
  EXPECT_EQ(st.failures.size(), 3u);
  fs::remove(FilmDir("a.mp4") + "/a.semantic.hjif");  // an output lost: no longer done
  st = ReadBatchStatus(options_.out_dir);
  EXPECT_EQ(st.done, 4);
  EXPECT_EQ(st.pending, 1);
  EXPECT_NE(st.ToText().find("9 films: 4 done, 3 failed, 1 duplicate, 0 running, 1 pending"),
            std::string::npos);
  // ... and a re-run redoes it.
  const BatchSummary s = RunLocalBatch(options_);
  EXPECT_EQ(Find(s, "a.mp4")->status, FilmStatus::kDone);
}

TEST_F(BatchTest, ShardsPartitionTheLibraryAndMatchAnUnshardedRun) {
  RunLocalBatch(options_);
  const auto unsharded = OutputFiles(options_.out_dir);

  BatchOptions sharded = options_;
  sharded.out_dir = dir_.path() + "/out-sharded";
  sharded.shard_count = 3;
  std::multiset<std::string> seen;
  for (int i = 0; i < 3; ++i) {
    sharded.shard_index = i;
    const BatchSummary s = RunLocalBatch(sharded);
    for (const FilmOutcome& f : s.films) seen.insert(f.path);
    EXPECT_TRUE(
        fs::exists(sharded.out_dir + "/.batch/shards/summary-" + std::to_string(i) + "-of-3.json"));
    const FilmOutcome* dup = Find(s, lib_.duplicate);
    if (dup != nullptr) {
      EXPECT_NE(Find(s, "a.mp4"), nullptr);  // a duplicate goes with its original
    }
  }
  EXPECT_EQ(static_cast<int>(seen.size()), lib_.total());
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), seen.size());  // disjoint
  EXPECT_EQ(OutputFiles(sharded.out_dir), unsharded);  // same relative names, same bytes
}

// A Linux file name is bytes: a film whose name is not UTF-8 is done, and the
// plan and summary (JSON) keep its exact path.
TEST_F(BatchTest, FilmNameThatIsNotUtf8IsDone) {
  const std::string name = "b\xff\xfe.mp4";
  WriteFile(lib_.root + "/" + name, "FAKEVIDEO b\n");
  const BatchSummary s = RunLocalBatch(options_);
  const FilmOutcome* film = Find(s, name);
  ASSERT_NE(film, nullptr);
  EXPECT_EQ(film->status, FilmStatus::kDone) << film->reason;
  EXPECT_EQ(film->path, lib_.root + "/" + name);
  EXPECT_TRUE(fs::is_regular_file(FilmDir(name) + "/b\xff\xfe.camera.csv"));
  // A second run reads the state back and skips it.
  EXPECT_EQ(Find(RunLocalBatch(options_), name)->status, FilmStatus::kSkipped);
}

// A single video file given as the library is a library of one.
TEST_F(BatchTest, AVideoFileIsALibraryOfOne) {
  options_.library = lib_.root + "/" + lib_.good.front();
  const BatchSummary s = RunLocalBatch(options_);
  ASSERT_EQ(s.films.size(), 1u);
  EXPECT_EQ(s.films[0].status, FilmStatus::kDone) << s.films[0].reason;
}

TEST_F(BatchTest, ManifestLibraryIsEquivalentToFolder) {
  WriteFile(dir_.path() + "/lib.csv",
            "title,path\nA,library/a.mp4\nJP,library/日本.mkv\nGone,library/missing.mp4\n");
  options_.library = dir_.path() + "/lib.csv";
  const BatchSummary s = RunLocalBatch(options_);
  ASSERT_EQ(s.films.size(), 3u);
  EXPECT_EQ(Find(s, "a.mp4")->status, FilmStatus::kDone);
  EXPECT_EQ(Find(s, "日本.mkv")->status, FilmStatus::kDone);
  EXPECT_NE(Find(s, "missing.mp4")->reason.find("no such file"), std::string::npos);
}

// A FIFO in a manifest would block the batch while hashing, before any film
// runs; /dev/zero would be hashed for ever. Both are failed films, each with
// one line, and the good film is done.
TEST_F(BatchTest, ManifestEntryThatIsNotARegularFileFailsAloneWithoutBlocking) {
  const std::string fifo = dir_.path() + "/library/pipe.mp4";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  WriteFile(dir_.path() + "/lib.txt", "library/a.mp4\nlibrary/pipe.mp4\n/dev/zero\n");
  options_.library = dir_.path() + "/lib.txt";
  const BatchSummary s = RunLocalBatch(options_);
  ASSERT_EQ(s.films.size(), 3u);
  EXPECT_EQ(Find(s, "a.mp4")->status, FilmStatus::kDone);
  EXPECT_EQ(Find(s, "pipe.mp4")->status, FilmStatus::kFailed);
  EXPECT_EQ(Find(s, "pipe.mp4")->reason, fifo + ": not a regular file");
  EXPECT_EQ(Find(s, "/dev/zero")->reason, "/dev/zero: not a regular file");
  // A manifest that is itself a FIFO is refused, not waited on.
  options_.library = fifo;
  try {
    RunLocalBatch(options_);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), fifo + ": not a regular file");
  }
}

TEST(BatchOptionsTest, CheckRejectsBadOptions) {
  BatchOptions o;
  o.library = "lib";
  o.out_dir = "out";
  EXPECT_NO_THROW(o.Check());
  BatchOptions bad = o;
  bad.models = {};
  EXPECT_THROW(bad.Check(), UsageError);
  bad = o;
  bad.models = {"../evil"};
  EXPECT_THROW(bad.Check(), UsageError);
  bad.models = {"cinematic", "bogus"};  // a usage error before any film is estimated
  EXPECT_THROW(bad.Check(), UsageError);
  bad.models = {"cinematic", "cinematic"};
  EXPECT_THROW(bad.Check(), UsageError);
  bad.models = {"cinematic", "semantic", "random", "none"};
  EXPECT_NO_THROW(bad.Check());
  bad = o;
  bad.shard_index = 2;
  bad.shard_count = 2;
  EXPECT_THROW(bad.Check(), UsageError);
  bad = o;
  bad.jobs = -1;
  EXPECT_THROW(bad.Check(), UsageError);
  bad = o;
  bad.out_dir = "";
  EXPECT_THROW(bad.Check(), UsageError);
}

TEST(BatchOptionsTest, StepKeysSeparateEstimateFromHapticsSettings) {
  BatchOptions a;
  BatchOptions b = a;
  b.haptics_args = {"--gain", "2"};
  EXPECT_EQ(EstimateStepKey(a), EstimateStepKey(b));
  EXPECT_NE(HapticsStepKey(a, "cinematic"), HapticsStepKey(b, "cinematic"));
  EXPECT_NE(HapticsStepKey(a, "cinematic"), HapticsStepKey(a, "semantic"));
  EXPECT_NE(SettingsHash(a), SettingsHash(b));
  b = a;
  b.estimate_args = {"--fast"};
  EXPECT_NE(EstimateStepKey(a), EstimateStepKey(b));
  EXPECT_NE(HapticsStepKey(a, "cinematic"), HapticsStepKey(b, "cinematic"));
}

}  // namespace
}  // namespace hapcine::batch

namespace hapcine::batch {
namespace {

// The counts batch reads from a camera path file holding `text` (in a folder
// of its own: tests run in parallel processes).
FilmOutcome CountsOfFile(const std::string& text) {
  const TempDir dir("batch_quality");
  const std::string file = dir.path() + "/film.camera.csv";
  { std::ofstream(file) << text; }
  FilmOutcome o;
  ReadShotQualityCounts(file, &o);
  return o;
}

// The summary's doubtful shots come from the camera path's header alone.
TEST(FilmRunnerTest, ShotQualityCountsFromTheCameraPathHeader) {
  const FilmOutcome o = CountsOfFile(
      "# fps=24\n# shot_quality.0=first:0 last:9 frames:10 lost:0 median_confidence:0.300 doubtful:0\n"
      "# shot_quality.1=first:10 last:29 frames:20 lost:3 median_confidence:0.100 doubtful:1\n"
      "# shot_quality.2=first:30 last:49 frames:20 lost:0 median_confidence:0.400 zoom_ambiguous:12 doubtful:0\n"
      "# shot_quality.3=first:50 last:59 frames:10 lost:0 median_confidence:0.400 zoom_ambiguous:0 doubtful:0\n"
      "# shot_quality.4=first:60 last:69 frames:10 lost:0 median_confidence:0.400 zoom_ambiguous:-5 doubtful:0\n"
      "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n# shot_quality.5=not a header: after the column row\n");
  EXPECT_EQ(o.shots, 5);
  EXPECT_EQ(o.doubtful_shots, 1);
  EXPECT_EQ(o.lost_frames, 3);
  EXPECT_EQ(o.zoom_ambiguous_shots, 1);  // 0 (every decision clear) and a negative count are not
  const FilmOutcome back = OutcomeFromJson(OutcomeToJson(o));
  EXPECT_EQ(back.shots, 5);
  EXPECT_EQ(back.doubtful_shots, 1);
  EXPECT_EQ(back.lost_frames, 3);
  EXPECT_EQ(back.zoom_ambiguous_shots, 1);
  // A summary written before the count existed reads as none.
  nlohmann::json old_json = OutcomeToJson(o);
  old_json.erase("zoom_ambiguous_shots");
  EXPECT_EQ(OutcomeFromJson(old_json).zoom_ambiguous_shots, 0);
  FilmOutcome none;
  ReadShotQualityCounts((std::filesystem::temp_directory_path() / "hapcine_no_such.camera.csv").string(), &none);
  EXPECT_EQ(none.shots, -1);
  EXPECT_EQ(none.zoom_ambiguous_shots, 0);
  EXPECT_EQ(CountsOfFile("# fps=24\nframe,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n").shots, -1);  // no summary
}

// A hand-edited header: a count no int holds is ignored (core's parser), and
// the sum of counts that each fit stops at the largest int.
TEST(FilmRunnerTest, ShotQualityCountsOfAHandEditedHeader) {
  const FilmOutcome o = CountsOfFile("# shot_quality.0=lost:2147483647\n# shot_quality.1=lost:2147483647\n"
                                     "# shot_quality.2=lost:1e30 zoom_ambiguous:99999999999\n"
                                     "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n");
  EXPECT_EQ(o.shots, 3);
  EXPECT_EQ(o.lost_frames, std::numeric_limits<int>::max());
  EXPECT_EQ(o.zoom_ambiguous_shots, 0);
}

// summary.txt names a film's doubtful and zoom-ambiguous shots, and only
// those films.
TEST(BatchSummaryTest, TextNamesDoubtfulAndZoomAmbiguousShots) {
  BatchSummary s;
  FilmOutcome both, zoom_only, clean;
  both.id = "both";
  both.status = zoom_only.status = clean.status = FilmStatus::kDone;
  both.shots = 4;
  both.doubtful_shots = 1;
  both.lost_frames = 7;
  both.zoom_ambiguous_shots = 2;
  zoom_only.id = "zoom_only";
  zoom_only.shots = 3;
  zoom_only.zoom_ambiguous_shots = 1;
  clean.id = "clean";
  clean.shots = 2;
  s.films = {both, zoom_only, clean};
  const std::string text = s.ToText();
  auto line_of = [&](const std::string& id) {
    const size_t at = text.find("  " + id);
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_NE(line_of("both").find("1 of 4 shots doubtful, 7 frames lost  2 of 4 shots zoom ambiguous"),
            std::string::npos)
      << text;
  EXPECT_NE(line_of("zoom_only").find("1 of 3 shots zoom ambiguous"), std::string::npos) << text;
  EXPECT_EQ(line_of("zoom_only").find("doubtful"), std::string::npos) << text;
  EXPECT_EQ(line_of("clean").find("shots"), std::string::npos) << text;
  EXPECT_EQ(s.ToJson()["films"][1]["zoom_ambiguous_shots"], 1);
}

}  // namespace
}  // namespace hapcine::batch
