#include "study/plan.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "core/error.h"
#include "study/json_util.h"
#include "study/results.h"
#include "study/test_fixtures.h"

namespace hapcine::study {
namespace {
using testing::MakeClip;
using testing::MakePaperClips;
using testing::MakeTempDir;

std::string Key(const Trial& t) {
  std::string k = t.clip + ":";
  for (const auto& c : t.first) k += c + "+";
  k += ">";
  for (const auto& c : t.second) k += c + "+";
  return k;
}

TEST(PlanTest, FourDistinctConditionsGiveTwelveTrialsPerClip) {
  const std::string dir = MakeTempDir("plan4");
  PlanOptions o;
  o.clips = {MakeClip(dir, "crane")};
  o.participants = 3;
  const StudyPlan plan = MakePlan(o, nullptr);
  ASSERT_EQ(plan.clips.size(), 1u);
  EXPECT_EQ(plan.clips[0].groups.size(), 4u);
  for (const auto& p : plan.participants) {
    EXPECT_EQ(p.trials.size(), 12u);
    // Every ordered pair of distinct conditions exactly once: a pair and its inverse.
    std::set<std::string> keys;
    for (const auto& t : p.trials) {
      EXPECT_NE(t.first, t.second);
      keys.insert(Key(t));
    }
    EXPECT_EQ(keys.size(), 12u);
  }
}

TEST(PlanTest, IdenticalTracksAreMergedLikeThePapersVertigo) {
  const std::string dir = MakeTempDir("plan3");
  PlanOptions o;
  o.clips = {MakeClip(dir, "vertigo", /*cinematic_equals_none=*/true)};
  o.participants = 2;
  const StudyPlan plan = MakePlan(o, nullptr);
  const auto& g = plan.clips[0].groups;
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0], (std::vector<std::string>{"cinematic", "none"}));
  EXPECT_EQ(plan.participants[0].trials.size(), 6u);
}

TEST(PlanTest, IdenticalMeansWithinOneMicrometre) {
  const std::string dir = MakeTempDir("tol");
  PlanOptions o;
  o.participants = 1;
  // Cinematic = none + 0.5 um everywhere: the same stimulus.
  o.clips = {MakeClip(dir, "a", true, 0.5e-6)};
  EXPECT_EQ(MakePlan(o, nullptr).clips[0].groups.size(), 3u);
  // + 2 um: different.
  o.clips = {MakeClip(dir, "b", true, 2e-6)};
  EXPECT_EQ(MakePlan(o, nullptr).clips[0].groups.size(), 4u);
}

TEST(PlanTest, PapersSevenClipsGiveSeventyEightTrials) {
  const std::string dir = MakeTempDir("paper");
  PlanOptions o;
  o.clips = MakePaperClips(dir);
  o.participants = 38;
  const StudyPlan plan = MakePlan(o, nullptr);
  EXPECT_EQ(TrialsPerParticipant(plan.clips), 78);  // 6 x 12 + 6 (6 x 6 + 3 couples, both orders)
  ASSERT_EQ(plan.participants.size(), 38u);
  EXPECT_EQ(plan.participants[0].id, "P01");
  EXPECT_EQ(plan.participants[37].id, "P38");
  for (const auto& p : plan.participants) {
    EXPECT_EQ(p.trials.size(), 78u);
    // Training: every clip once, all with the participant's one condition.
    ASSERT_EQ(p.training.size(), 7u);
    std::set<std::string> clips;
    for (const auto& t : p.training) {
      EXPECT_EQ(t.condition, p.training_condition);
      clips.insert(t.clip);
    }
    EXPECT_EQ(clips.size(), 7u);
  }
  // Training conditions are drawn at random: with 38 participants more than one shows up.
  std::set<std::string> training_conditions;
  for (const auto& p : plan.participants) training_conditions.insert(p.training_condition);
  EXPECT_GT(training_conditions.size(), 1u);
}

TEST(PlanTest, RandomisationIsReproducibleBySeedAndDiffersAcrossParticipants) {
  const std::string dir = MakeTempDir("seed");
  PlanOptions o;
  o.clips = MakePaperClips(dir);
  o.participants = 5;
  o.seed = 1234;
  const StudyPlan a = MakePlan(o, nullptr);
  const StudyPlan b = MakePlan(o, nullptr);
  EXPECT_EQ(a.plan_id, b.plan_id);
  for (size_t p = 0; p < a.participants.size(); ++p)
    for (size_t t = 0; t < a.participants[p].trials.size(); ++t)
      EXPECT_EQ(Key(a.participants[p].trials[t]), Key(b.participants[p].trials[t]));
  // Different participants, different orders.
  auto order = [](const ParticipantPlan& p) {
    std::string s;
    for (const auto& t : p.trials) s += Key(t) + ";";
    return s;
  };
  std::set<std::string> orders;
  for (const auto& p : a.participants) orders.insert(order(p));
  EXPECT_EQ(orders.size(), a.participants.size());
  // Another seed, another plan.
  o.seed = 1235;
  const StudyPlan c = MakePlan(o, nullptr);
  EXPECT_NE(c.plan_id, a.plan_id);
  EXPECT_NE(order(c.participants[0]), order(a.participants[0]));
  // More participants leave the first ones' orders unchanged.
  o.seed = 1234;
  o.participants = 8;
  const StudyPlan d = MakePlan(o, nullptr);
  EXPECT_EQ(order(d.participants[4]), order(a.participants[4]));
  EXPECT_EQ(d.participants[4].training_condition, a.participants[4].training_condition);
}

TEST(PlanTest, FileRoundTripAndTamperDetection) {
  const std::string dir = MakeTempDir("file");
  PlanOptions o;
  o.clips = {MakeClip(dir, "crane"), MakeClip(dir, "vertigo", true)};
  o.participants = 4;
  const StudyPlan plan = MakePlan(o, nullptr);
  const std::string path = dir + "/plan.json";
  WritePlanFile(plan, path);
  const StudyPlan back = ReadPlanFile(path);
  EXPECT_EQ(back.plan_id, plan.plan_id);
  EXPECT_EQ(back.participants[3].trials.size(), 18u);
  EXPECT_EQ(back.Participant("3").id, "P03");
  EXPECT_EQ(back.Participant("P04").number, 4);
  EXPECT_THROW(back.Participant("P05"), UsageError);
  // Swap two trials by hand: the plan id no longer matches.
  auto j = ReadJsonFile(path);
  std::swap(j["participants"][0]["trials"][0]["first"],
            j["participants"][0]["trials"][0]["second"]);
  std::ofstream(dir + "/edited.json") << j.dump();
  try {
    ReadPlanFile(dir + "/edited.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("edited"), std::string::npos) << e.what();
  }
  std::ofstream(dir + "/foreign.json") << R"({"format":"something else"})";
  EXPECT_THROW(ReadPlanFile(dir + "/foreign.json"), Error);
  std::ofstream(dir + "/broken.json") << R"({"format":"hapcine-study-plan", "version": 1, "pla)";
  EXPECT_THROW(ReadPlanFile(dir + "/broken.json"), Error);
}

// A plan edited by hand, with its plan_id recomputed so only the content is
// wrong: the message read back, or "" if it loaded.
std::string LoadError(const StudyPlan& edited, const std::string& path) {
  StudyPlan p = edited;
  p.plan_id = ComputePlanId(p);
  WritePlanFile(p, path);
  try {
    ReadPlanFile(path);
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

TEST(PlanTest, LoadingValidatesEveryTrialAndGroup) {
  const std::string dir = MakeTempDir("validate");
  PlanOptions o;
  o.clips = {MakeClip(dir, "crane"), MakeClip(dir, "vertigo", true)};
  o.participants = 2;
  const StudyPlan plan = MakePlan(o, nullptr);
  const std::string path = dir + "/edited.json";
  ASSERT_EQ(LoadError(plan, path), "");
  const std::string at = path + ": participant P02 trial 3: ";
  struct Case {
    std::function<void(StudyPlan*)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](StudyPlan* p) { p->participants[1].trials[3].first.clear(); },
       at + "first group is empty"},
      {[](StudyPlan* p) { p->participants[1].trials[3].second = {"bogus"}; },
       at + "unknown condition 'bogus' in second group"},
      {[](StudyPlan* p) { p->participants[1].trials[3].clip = "nosuch"; },
       at + "unknown clip 'nosuch'"},
      {[](StudyPlan* p) { p->participants[1].trials[3].second = p->participants[1].trials[3].first; },
       at + "both groups are the same"},
      {[](StudyPlan* p) {
         Trial& t = p->participants[1].trials[3];
         t.first = {"cinematic", "semantic"};  // not one of the clip's groups
       },
       at + "first group is not a group of clip"},
      {[](StudyPlan* p) { p->participants[0].training_condition = "bogus"; },
       path + ": participant P01: unknown training condition 'bogus'"},
      {[](StudyPlan* p) { p->participants[0].training[0].clip = "nosuch"; },
       path + ": participant P01 training: unknown clip 'nosuch'"},
      {[](StudyPlan* p) { p->clips[0].groups.push_back({}); },
       path + ": clip 'crane': empty group"},
      {[](StudyPlan* p) { p->clips[0].groups.pop_back(); },
       path + ": clip 'crane': groups do not cover every condition"},
      {[](StudyPlan* p) { p->participants.clear(); }, path + ": no participants"},
  };
  for (const Case& c : cases) {
    StudyPlan edited = plan;
    c.edit(&edited);
    const std::string message = LoadError(edited, path);
    EXPECT_EQ(message.substr(0, c.message.size()), c.message) << message;
  }
}

// Plans and results that are not regular files: one line, never read
// (/dev/zero never ends; a directory used to be "not valid JSON").
TEST(PlanTest, PlanAndResultsThatAreNotRegularFilesAreRefused) {
  const std::string dir = MakeTempDir("devices");
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    const std::string reason = bad == dir ? ": is a directory" : ": not a regular file";
    for (int which = 0; which < 2; ++which) {
      try {
        if (which == 0) ReadPlanFile(bad);
        if (which == 1) ReadResultsFile(bad);
        ADD_FAILURE() << "no error for " << bad;
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), bad + reason);
      }
    }
  }
}

TEST(PlanTest, DirectoryLayoutAndBadInput) {
  const std::string dir = MakeTempDir("layout");
  const std::string clip_dir = dir + "/tilting";
  std::filesystem::create_directory(clip_dir);
  std::ofstream(clip_dir + "/video.mkv") << "stand-in";
  for (const char* c : {"cinematic", "semantic", "none", "random"})
    WriteHapticTrackFile(testing::MakeTrack(c, std::string(c) == "none" ? 0 : int(c[0])),
                         clip_dir + "/" + c + ".haptic.csv");
  PlanOptions o;
  o.clips = {clip_dir};
  o.participants = 1;
  const StudyPlan plan = MakePlan(o, nullptr);
  EXPECT_EQ(plan.clips[0].name, "tilting");
  EXPECT_EQ(plan.participants[0].trials.size(), 12u);

  // A missing track names the clip and the expected file.
  std::filesystem::remove(clip_dir + "/random.haptic.csv");
  try {
    MakePlan(o, nullptr);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("random.haptic.csv"), std::string::npos) << e.what();
  }
  o.clips = {dir + "/nope.mp4"};
  EXPECT_THROW(MakePlan(o, nullptr), Error);
  // A corrupt track is reported, not planned around.
  const std::string v = MakeClip(dir, "bad");
  std::ofstream(dir + "/bad.semantic.haptic.csv") << "garbage\n";
  o.clips = {v};
  EXPECT_THROW(MakePlan(o, nullptr), Error);
  // Options.
  PlanOptions bad;
  EXPECT_THROW(bad.Check(), UsageError);  // no clips
  bad.clips = {v};
  bad.conditions = {"cinematic"};
  EXPECT_THROW(bad.Check(), UsageError);
  bad.conditions = {"a", "a"};
  EXPECT_THROW(bad.Check(), UsageError);
  bad.conditions = {"a", "b"};
  bad.participants = 0;
  EXPECT_THROW(bad.Check(), UsageError);
}

}  // namespace
}  // namespace hapcine::study
