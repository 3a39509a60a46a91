#include "study/session.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "study/json_util.h"
#include "study/plan.h"
#include "study/results.h"
#include "study/test_fixtures.h"

namespace hapcine::study {
namespace {
using testing::MakeClip;
using testing::MakeTempDir;

struct Fixture {
  std::string dir, plan_path;
  StudyPlan plan;
};

Fixture MakeStudy(const std::string& tag) {
  Fixture f;
  f.dir = MakeTempDir(tag);
  PlanOptions o;
  o.clips = {MakeClip(f.dir, "crane"), MakeClip(f.dir, "vertigo", true)};  // 12 + 6 trials
  o.participants = 3;
  o.seed = 7;
  f.plan = MakePlan(o, nullptr);
  f.plan_path = f.dir + "/plan.json";
  WritePlanFile(f.plan, f.plan_path);
  return f;
}

std::string WriteResponses(const std::string& path, const std::vector<int>& answers) {
  std::ofstream out(path);
  out << "# scripted answers\n";
  for (int a : answers) out << a << "\n";
  return path;
}

size_t CountLines(const std::string& path) {
  std::ifstream in(path);
  size_t n = 0;
  std::string line;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(SessionTest, ResumesAfterInterruptionWithNothingLostOrDuplicated) {
  Fixture f = MakeStudy("resume");
  ASSERT_EQ(f.plan.participants[1].trials.size(), 18u);
  std::vector<int> all;
  for (int i = 0; i < 18; ++i) all.push_back(1 + (i * 7 % 3 == 0));
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "P02";
  const std::string played = f.dir + "/played.txt";
  o.player_cmd = "/bin/sh -c 'echo \"$0\" >> " + played + "' {condition}";
  // First sitting: answers for 9 trials, then the input runs out (a break).
  o.responses_path = WriteResponses(f.dir + "/r1.txt", {all.begin(), all.begin() + 9});
  std::istringstream no_input;
  std::ostringstream log;
  RunSummary s1 = RunSession(o, no_input, log);
  EXPECT_FALSE(s1.complete);
  EXPECT_EQ(s1.answered_now, 9);
  EXPECT_FALSE(std::filesystem::exists(s1.results_path));
  EXPECT_EQ(s1.journal_path, f.dir + "/P02.journal.jsonl");
  // 2 training clips + 9 pairs; no pair is played once the answers run out.
  EXPECT_EQ(CountLines(played), 2u + 9 * 2);

  // A crash in the middle of writing the next record leaves a torn line.
  { std::ofstream(s1.journal_path, std::ios::app) << R"({"type":"trial","index":)"; }

  // Second sitting: the remaining 9 answers.
  o.responses_path = WriteResponses(f.dir + "/r2.txt", {all.begin() + 9, all.end()});
  RunSummary s2 = RunSession(o, no_input, log);
  EXPECT_EQ(s2.answered_before, 9);
  EXPECT_EQ(s2.answered_now, 9);
  ASSERT_TRUE(s2.complete) << log.str();
  EXPECT_EQ(CountLines(played), 2u + 18 * 2);  // training is not repeated on resume

  const ParticipantResults r = ReadResultsFile(s2.results_path);
  EXPECT_EQ(r.plan_id, f.plan.plan_id);
  EXPECT_EQ(r.participant, "P02");
  ASSERT_EQ(r.trials.size(), 18u);
  std::set<int> idx;
  for (size_t i = 0; i < r.trials.size(); ++i) {
    idx.insert(r.trials[i].index);
    EXPECT_EQ(r.trials[i].choice, all[r.trials[i].index]) << i;
    EXPECT_EQ(r.trials[i].first, f.plan.participants[1].trials[r.trials[i].index].first);
  }
  EXPECT_EQ(idx.size(), 18u);
  // Journal: header, started, training_done, 9 trials, started, 9 trials.
  EXPECT_EQ(CountLines(s2.journal_path), 1u + 1 + 1 + 9 + 1 + 9);

  // Running again once complete asks nothing and rewrites the same answers.
  o.responses_path = WriteResponses(f.dir + "/r3.txt", {});
  RunSummary s3 = RunSession(o, no_input, log);
  EXPECT_TRUE(s3.complete);
  EXPECT_EQ(s3.answered_now, 0);
  EXPECT_EQ(ReadResultsFile(s3.results_path).trials.size(), 18u);
}

TEST(SessionTest, PlaysTheRightTracksInOrderAndReadsTypedAnswers) {
  Fixture f = MakeStudy("player");
  const std::string log_path = f.dir + "/played.txt";
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "1";
  o.device = "none";
  o.results_path = f.dir + "/out/sub/p1.results.json";  // folders created by the run
  o.player_cmd =
      "/bin/sh -c 'echo \"$0 $1 $2 $3\" >> " + log_path + "' {clip} {condition} {track} {device}";
  // Typed answers with noise: invalid input is asked again, "r" replays.
  std::string typed;
  for (int i = 0; i < 18; ++i) typed += (i == 0 ? "x\nr\n2\n" : "1\n");
  std::istringstream in(typed);
  std::ostringstream out;
  const RunSummary s = RunSession(o, in, out);
  ASSERT_TRUE(s.complete) << out.str();
  EXPECT_EQ(s.journal_path, f.dir + "/out/sub/p1.journal.jsonl");
  // 2 training clips + 18 trials x 2 stimuli + one replayed pair.
  std::ifstream played(log_path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(played, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 2u + 36 + 2);
  const ParticipantPlan& p = f.plan.participants[0];
  const StudyClip& clip0 = f.plan.Clip(p.trials[0].clip);
  const std::string want_first = p.trials[0].clip + " " + p.trials[0].first[0] + " " +
                                 clip0.tracks.at(p.trials[0].first[0]).path + " none";
  EXPECT_EQ(lines[2], want_first);
  EXPECT_EQ(lines[4], want_first);  // replayed
  EXPECT_EQ(lines[0].substr(lines[0].find(' ') + 1, p.training_condition.size()),
            p.training_condition);
  const ParticipantResults r = ReadResultsFile(s.results_path);
  EXPECT_EQ(r.trials[0].choice, 2);
  EXPECT_EQ(r.trials[1].choice, 1);
  EXPECT_EQ(r.device, "none");
}

TEST(SessionTest, FailuresKeepTheJournalAndRefuseForeignState) {
  Fixture f = MakeStudy("fail");
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "P03";
  o.player_cmd = "/bin/false";
  o.responses_path = WriteResponses(f.dir + "/r.txt", std::vector<int>(18, 1));
  std::istringstream in;
  std::ostringstream out;
  EXPECT_THROW(RunSession(o, in, out), Error);  // the player failed
  o.player_cmd = "/nonexistent/player";
  EXPECT_THROW(RunSession(o, in, out), Error);
  // Half done, then the journal is copied to another participant's name.
  o.player_cmd = "/bin/true";
  o.responses_path = WriteResponses(f.dir + "/r.txt", std::vector<int>(5, 2));
  const RunSummary s = RunSession(o, in, out);
  EXPECT_EQ(s.answered_now, 5);
  std::filesystem::copy_file(s.journal_path, f.dir + "/P01.journal.jsonl");
  o.participant = "P01";
  EXPECT_THROW(RunSession(o, in, out), Error);
  // A corrupt line in the middle is an error, not silently skipped.
  o.participant = "P03";
  {
    std::ifstream inj(s.journal_path);
    std::stringstream ss;
    ss << inj.rdbuf();
    std::string text = ss.str();
    text.insert(text.find('\n') + 1, "garbage\n");
    std::ofstream(s.journal_path) << text;
  }
  EXPECT_THROW(RunSession(o, in, out), Error);
  // Tracks changed after planning are refused.
  Fixture g = MakeStudy("changed");
  WriteHapticTrackFile(testing::MakeTrack("semantic", 5), g.dir + "/crane.semantic.haptic.csv");
  o.plan_path = g.plan_path;
  EXPECT_THROW(RunSession(o, in, out), Error);
  // Bad options.
  RunOptions bad = o;
  bad.device = "holodeck";
  EXPECT_THROW(bad.Check(), UsageError);
  bad = o;
  bad.participant = "P99";
  EXPECT_THROW(RunSession(bad, in, out), UsageError);
  bad = o;
  std::ofstream(f.dir + "/bad_responses.txt") << "1\n3\n";
  bad.plan_path = f.plan_path;
  bad.responses_path = f.dir + "/bad_responses.txt";
  EXPECT_THROW(RunSession(bad, in, out), Error);
}

// A plan edited by hand (its id recomputed) that `study run` must refuse with
// one Error naming the plan, before playing anything.
TEST(SessionTest, EditedPlanIsRefusedWhenLoaded) {
  Fixture f = MakeStudy("edited");
  RunOptions o;
  o.plan_path = f.dir + "/edited.json";
  o.participant = "P01";
  o.player_cmd = "/bin/true";
  o.responses_path = WriteResponses(f.dir + "/r.txt", std::vector<int>(18, 1));
  std::istringstream in;
  std::ostringstream out;
  for (const std::vector<std::string>& first :
       {std::vector<std::string>{}, std::vector<std::string>{"bogus"}}) {
    StudyPlan p = f.plan;
    p.participants[0].trials[0].first = first;  // an empty group; an unknown condition
    p.plan_id = ComputePlanId(p);
    WritePlanFile(p, o.plan_path);
    try {
      RunSession(o, in, out);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), o.plan_path);
      EXPECT_EQ(e.reason().rfind("participant P01 trial 0: ", 0), 0u) << e.what();
    }
  }
}

// A track that is not a regular file (/dev/zero, a FIFO) is refused before
// the first clip plays, instead of hanging the player.
TEST(SessionTest, TrackThatIsNotARegularFileIsRefused) {
  Fixture f = MakeStudy("devzero");
  RunOptions o;
  o.plan_path = f.dir + "/devzero.json";
  o.participant = "P01";
  o.player_cmd = "/bin/true";
  o.verify_hashes = false;  // hashing would refuse it too; the check must not depend on it
  o.responses_path = WriteResponses(f.dir + "/r.txt", std::vector<int>(18, 1));
  StudyPlan p = f.plan;
  p.clips[0].tracks["semantic"].path = "/dev/zero";
  p.plan_id = ComputePlanId(p);
  WritePlanFile(p, o.plan_path);
  std::istringstream in;
  std::ostringstream out;
  try {
    RunSession(o, in, out);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/zero: not a regular file");
  }
  EXPECT_EQ(out.str().find("Training"), std::string::npos) << out.str();
}

// A plan whose sessions end with three questions, one of each type.
Fixture MakeStudyWithQuestionnaire(const std::string& tag) {
  Fixture f;
  f.dir = MakeTempDir(tag);
  PlanOptions o;
  o.clips = {MakeClip(f.dir, "crane")};  // 12 trials
  o.participants = 1;
  o.questionnaire = {
      {"comfort", "Comfortable?", "likert", 1, 5, "not at all", "very", {}},
      {"metaphor", "Did you recognise a motion?", "choice", 1, 5, "", "", {"yes", "no"}},
      {"comments", "Comments?", "text", 1, 5, "", "", {}}};
  f.plan = MakePlan(o, nullptr);
  f.plan_path = f.dir + "/plan.json";
  WritePlanFile(f.plan, f.plan_path);
  return f;
}

std::string WriteLines(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const auto& l : lines) out << l << "\n";
  return path;
}

TEST(SessionTest, QuestionnaireAfterTheLastTrialAsksAgainOnInvalidAnswers) {
  Fixture f = MakeStudyWithQuestionnaire("questions");
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "P01";
  o.player_cmd = "/bin/true";
  std::vector<std::string> lines(12, "2");
  for (const char* a : {"9", "4", "maybe", "1", "like a crab walk # with a comment"})
    lines.push_back(a);
  o.responses_path = WriteLines(f.dir + "/r.txt", lines);
  std::istringstream no_input;
  std::ostringstream log;
  const RunSummary s = RunSession(o, no_input, log);
  ASSERT_TRUE(s.complete) << log.str();
  EXPECT_EQ(s.questions, 3);
  EXPECT_EQ(s.questions_answered, 3);
  EXPECT_NE(log.str().find("Question 1/3: Comfortable?"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("Please type a whole number from 1 to 5."), std::string::npos);
  EXPECT_NE(log.str().find("Please type a number from 1 to 2."), std::string::npos);
  const ParticipantResults r = ReadResultsFile(s.results_path);
  ASSERT_EQ(r.questionnaire.size(), 3u);
  EXPECT_EQ(r.questionnaire[0].question.id, "comfort");
  EXPECT_EQ(r.questionnaire[0].answer, nlohmann::json(4));
  EXPECT_EQ(r.questionnaire[1].answer, nlohmann::json("yes"));
  EXPECT_EQ(r.questionnaire[2].answer, nlohmann::json("like a crab walk"));
  EXPECT_EQ(r.questionnaire[0].question.max_label, "very");
  // Typed on stdin: the same questions, one line each; "q" stops for now.
  Fixture g = MakeStudyWithQuestionnaire("questions_typed");
  o.plan_path = g.plan_path;
  o.responses_path.clear();
  std::string typed_lines;
  for (int i = 0; i < 12; ++i) typed_lines += "1\n";
  std::istringstream typed(typed_lines + "5\nq\n");
  std::ostringstream out;
  const RunSummary t = RunSession(o, typed, out);
  EXPECT_FALSE(t.complete) << out.str();
  EXPECT_EQ(t.questions_answered, 1);
  EXPECT_NE(out.str().find("Stopped at the questionnaire after 1 of 3 questions"),
            std::string::npos)
      << out.str();
}

TEST(SessionTest, InterruptedQuestionnaireResumesWithoutRedoingTrials) {
  Fixture f = MakeStudyWithQuestionnaire("questions_resume");
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "P01";
  const std::string played = f.dir + "/played.txt";
  o.player_cmd = "/bin/sh -c 'echo \"$0\" >> " + played + "' {condition}";
  std::vector<std::string> lines(12, "1");
  lines.push_back("3");
  o.responses_path = WriteLines(f.dir + "/r1.txt", lines);
  std::istringstream no_input;
  std::ostringstream log;
  const RunSummary s1 = RunSession(o, no_input, log);
  EXPECT_FALSE(s1.complete);
  EXPECT_EQ(s1.answered_now, 12);
  EXPECT_EQ(s1.questions_answered, 1);
  EXPECT_FALSE(std::filesystem::exists(s1.results_path));
  const size_t plays = CountLines(played);
  EXPECT_EQ(plays, 1u + 12 * 2);
  // A crash while journalling the next answer leaves a torn line.
  { std::ofstream(s1.journal_path, std::ios::app) << R"({"type":"answer","id":"met)"; }

  o.responses_path = WriteLines(f.dir + "/r2.txt", {"no", "smooth"});
  std::ostringstream log2;
  const RunSummary s2 = RunSession(o, no_input, log2);
  ASSERT_TRUE(s2.complete) << log2.str();
  EXPECT_EQ(s2.answered_before, 12);
  EXPECT_EQ(s2.answered_now, 0);
  EXPECT_EQ(CountLines(played), plays);  // nothing played again
  EXPECT_NE(log2.str().find("12 of 12 trials already answered, 1 of 3 questions"),
            std::string::npos)
      << log2.str();
  EXPECT_EQ(log2.str().find("Question 1/3"), std::string::npos);  // not asked again
  const ParticipantResults r = ReadResultsFile(s2.results_path);
  ASSERT_EQ(r.questionnaire.size(), 3u);
  EXPECT_EQ(r.questionnaire[0].answer, nlohmann::json(3));
  EXPECT_EQ(r.questionnaire[1].answer, nlohmann::json("no"));
  EXPECT_EQ(r.questionnaire[2].answer, nlohmann::json("smooth"));

  // An answer in the journal that does not fit its question is refused.
  {
    std::ofstream(s1.journal_path, std::ios::app)
        << R"({"type":"answer","id":"comfort","answer":7,"answered_utc":"x"})"
        << "\n";
  }
  try {
    RunSession(o, no_input, log2);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        s1.journal_path + ": questionnaire question 'comfort': answer 7 does not fit the question");
  }
}

TEST(SessionTest, ResultsWithoutQuestionnaireHaveNoQuestionnaireKey) {
  Fixture f = MakeStudy("no_questions");
  RunOptions o;
  o.plan_path = f.plan_path;
  o.participant = "P03";
  o.player_cmd = "/bin/true";
  o.responses_path = WriteResponses(f.dir + "/r.txt", std::vector<int>(18, 1));
  std::istringstream no_input;
  std::ostringstream log;
  const RunSummary s = RunSession(o, no_input, log);
  ASSERT_TRUE(s.complete) << log.str();
  EXPECT_EQ(log.str().find("Questionnaire"), std::string::npos);
  EXPECT_FALSE(ReadJsonFile(s.results_path).contains("questionnaire"));
  EXPECT_TRUE(ReadResultsFile(s.results_path).questionnaire.empty());
}

}  // namespace
}  // namespace hapcine::study
