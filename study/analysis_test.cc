#include "study/analysis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "core/error.h"
#include "study/json_util.h"
#include "study/plan.h"
#include "study/report.h"
#include "study/results.h"
#include "study/test_fixtures.h"

namespace hapcine::study {
namespace {
using testing::MakePaperClips;
using testing::MakeTempDir;

bool Has(const std::vector<std::string>& g, const std::string& c) {
  return std::find(g.begin(), g.end(), c) != g.end();
}

// Synthetic participants with a known ranking: cinematic always wins, random
// always loses; semantic vs none: the first stimulus shown (no preference,
// each wins one of its pair and inverse).
std::vector<ParticipantResults> Synthesize(const StudyPlan& plan) {
  std::vector<ParticipantResults> out;
  for (const auto& p : plan.participants) {
    ParticipantResults r;
    r.source = p.id + ".results.json";
    r.plan_id = plan.plan_id;
    r.participant = p.id;
    r.device = "sim";
    r.conditions = plan.conditions;
    for (const auto& c : plan.clips) r.clips.push_back({c.name, c.groups});
    r.training_condition = p.training_condition;
    r.started_utc = r.completed_utc = "2026-11-22T08:00:00Z";
    for (const auto& t : p.trials) {
      TrialResult tr;
      tr.index = t.index;
      tr.clip = t.clip;
      tr.first = t.first;
      tr.second = t.second;
      auto rank = [](const std::vector<std::string>& g) {
        if (Has(g, "cinematic")) return 3;
        if (Has(g, "random")) return 0;
        return 1;  // semantic or none
      };
      const int a = rank(t.first), b = rank(t.second);
      tr.choice = a > b ? 1 : a < b ? 2 : 1;  // tie: the first stimulus
      tr.response_time_s = 0.8;
      tr.answered_utc = r.completed_utc;
      r.trials.push_back(tr);
    }
    out.push_back(r);
  }
  return out;
}

StudyPlan PaperPlan(const std::string& dir, int participants, uint64_t seed) {
  PlanOptions o;
  o.clips = MakePaperClips(dir);
  o.participants = participants;
  o.seed = seed;
  return MakePlan(o, nullptr);
}

TEST(AnalysisTest, KnownWinner) {
  const std::string dir = MakeTempDir("analysis");
  const StudyPlan plan = PaperPlan(dir, 12, 3);
  const StudyAnalysis a = AnalyzeStudy(Synthesize(plan));
  ASSERT_EQ(a.conditions, (std::vector<std::string>{"cinematic", "semantic", "none", "random"}));
  // Cinematic wins every comparison it is in, except on Vertigo where it is
  // the same stimulus as "none" and shares that group's fate.
  const auto& m = a.overall.mean;
  EXPECT_GT(m[0], 0.9);
  EXPECT_DOUBLE_EQ(m[3], 0.0);  // random never chosen
  EXPECT_GT(m[0], m[1]);
  EXPECT_GT(m[0], m[2]);
  for (double v : m) {
    EXPECT_GE(v, 0);
    EXPECT_LE(v, 1);
  }
  // By hand, crane (4 groups): cinematic is in 6 trials and wins all -> 1;
  // random 0; semantic and none each beat random twice and split their 2
  // mutual trials 1:1 -> (2 + 1)/6 = 0.5.
  const ScoreTable& crane = a.per_clip[0];
  EXPECT_EQ(crane.label, "crane");
  for (const auto& s : crane.score) {
    EXPECT_DOUBLE_EQ(s[0], 1.0);
    EXPECT_DOUBLE_EQ(s[1], 0.5);
    EXPECT_DOUBLE_EQ(s[2], 0.5);
    EXPECT_DOUBLE_EQ(s[3], 0.0);
  }
  // Vertigo (3 groups, 4 trials each): the cinematic/none group beats random
  // and semantic -> 1 for both conditions.
  const ScoreTable& vertigo = a.per_clip[6];
  EXPECT_EQ(vertigo.label, "vertigo");
  for (const auto& s : vertigo.score) {
    EXPECT_DOUBLE_EQ(s[0], 1.0);
    EXPECT_DOUBLE_EQ(s[2], 1.0);
    EXPECT_DOUBLE_EQ(s[1], 0.5);  // semantic: loses twice to cinematic==none, beats random twice
  }
  // Cinematic vs none on Vertigo: one stimulus -> no test, p = 1, and not
  // counted in Holm's family: the other 5 pairs are adjusted as 5 hypotheses.
  std::vector<double> raw;
  for (const auto& pt : vertigo.pairwise) {
    const bool merged = pt.a == "cinematic" && pt.b == "none";
    EXPECT_EQ(pt.same_stimulus, merged) << pt.a << " " << pt.b;
    if (merged) {
      EXPECT_EQ(pt.wilcoxon.n_used, 0);
      EXPECT_EQ(pt.p_holm, 1);
    } else {
      raw.push_back(pt.wilcoxon.p);
    }
  }
  ASSERT_EQ(raw.size(), 5u);
  const std::vector<double> adj = HolmAdjust(raw);
  for (size_t i = 0, j = 0; i < vertigo.pairwise.size(); ++i) {
    if (!vertigo.pairwise[i].same_stimulus) {
      EXPECT_DOUBLE_EQ(vertigo.pairwise[i].p_holm, adj[j++]);
    }
  }
  // The overall table merges nothing.
  for (const auto& pt : a.overall.pairwise) EXPECT_FALSE(pt.same_stimulus);
  // Tests: Friedman significant; cinematic > none and random < all, Holm-adjusted.
  ASSERT_TRUE(a.overall.friedman.valid);
  EXPECT_LT(a.overall.friedman.p, 1e-4);
  for (const auto& pt : a.overall.pairwise) {
    if (pt.a == "cinematic" || pt.b == "random") {
      EXPECT_LT(pt.p_holm, 0.05) << pt.a << " " << pt.b;
    }
    EXPECT_GE(pt.p_holm, pt.wilcoxon.p);
  }

  const std::string text = FormatReport(a);
  EXPECT_NE(text.find("Friedman chi-squared"), std::string::npos);
  EXPECT_NE(text.find("vertigo"), std::string::npos);
  const auto written = WriteReport(a, dir + "/report");
  ASSERT_EQ(written.size(), 4u);
  std::ifstream svg(dir + "/report.sequences.svg");
  std::string s((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_EQ(s.rfind("<svg", 0), 0u);
  EXPECT_NE(s.find("</svg>"), std::string::npos);
  // 7 sequences x 4 conditions bars, + 4 legend swatches + background.
  size_t rects = 0;
  for (size_t pos = s.find("<rect"); pos != std::string::npos; pos = s.find("<rect", pos + 1))
    ++rects;
  EXPECT_EQ(rects, 7u * 4 + 4 + 1);
  EXPECT_EQ(ReadJsonFile(dir + "/report.json")["plan_id"], plan.plan_id);
}

TEST(AnalysisTest, NoPreferenceGivesNoSignificance) {
  const std::string dir = MakeTempDir("nopref");
  const StudyPlan plan = PaperPlan(dir, 10, 9);
  auto results = Synthesize(plan);
  // Overwrite with answers that always pick the first stimulus: every
  // condition is first in exactly half its trials -> every score 0.5.
  for (auto& r : results)
    for (auto& t : r.trials) t.choice = 1;
  const StudyAnalysis a = AnalyzeStudy(results);
  for (double m : a.overall.mean) EXPECT_DOUBLE_EQ(m, 0.5);
  EXPECT_FALSE(a.overall.friedman.valid);  // every block all ties
  for (const auto& pt : a.overall.pairwise) EXPECT_EQ(pt.p_holm, 1);
  EXPECT_FALSE(a.overall.normality[0].valid);  // constant scores
  EXPECT_NE(FormatReport(a).find("n/a"), std::string::npos);
}

TEST(AnalysisTest, RejectsMixedPlansCorruptAndForeignFiles) {
  const std::string dir = MakeTempDir("reject");
  const StudyPlan plan = PaperPlan(dir, 3, 1);
  const auto results = Synthesize(plan);
  for (const auto& r : results) WriteResultsFile(r, dir + "/" + r.participant + ".results.json");
  // Round trip.
  const ParticipantResults back = ReadResultsFile(dir + "/P01.results.json");
  EXPECT_EQ(back.trials.size(), 78u);

  // Another plan (other seed) -> error naming the file.
  const StudyPlan other = PaperPlan(MakeTempDir("reject2"), 3, 2);
  auto mixed = results;
  auto foreign_plan = Synthesize(other);
  foreign_plan[2].source = "other/P03.results.json";
  mixed.push_back(foreign_plan[2]);
  try {
    AnalyzeStudy(mixed);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "other/P03.results.json");
    EXPECT_NE(e.reason().find("plans cannot be mixed"), std::string::npos);
  }
  // The same participant twice.
  auto dup = results;
  dup.push_back(results[0]);
  EXPECT_THROW(AnalyzeStudy(dup), Error);
  EXPECT_THROW(AnalyzeStudy({}), UsageError);

  auto expect_rejected = [&](const std::string& name, const std::string& text,
                             const std::string& why) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    try {
      ReadResultsFile(path);
      ADD_FAILURE() << name << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), path);
      EXPECT_NE(e.reason().find(why), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  std::ifstream in(dir + "/P01.results.json");
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expect_rejected("truncated.json", good.substr(0, good.size() / 2), "not valid JSON");
  expect_rejected("plan_as_results.json", PlanToJson(plan).dump(),
                  "not a hapcine study results file");
  expect_rejected("array.json", "[1,2,3]", "not a hapcine study results file");
  auto j = nlohmann::json::parse(good);
  auto k = j;
  k["trials"][5]["choice"] = 3;
  expect_rejected("choice3.json", k.dump(), "choice must be 1 or 2");
  k = j;
  k["trials"].erase(k["trials"].begin() + 10);
  expect_rejected("missing.json", k.dump(), "incomplete");
  k = j;
  k["trials"][4] = k["trials"][3];
  expect_rejected("dup.json", k.dump(), "recorded twice");
  k = j;
  k["trials"][0]["first"] = {"telepathy"};
  expect_rejected("unknown.json", k.dump(), "not part of the design");
  k = j;
  k.erase("plan_id");
  expect_rejected("noid.json", k.dump(), "plan_id");
  k = j;
  k["trials"][0]["response_time_s"] = -1;
  expect_rejected("neg.json", k.dump(), "negative");
  k = j;
  k["version"] = 99;
  expect_rejected("version.json", k.dump(), "version");
  EXPECT_THROW(ReadResultsFile(dir + "/absent.json"), Error);
}

TEST(AnalysisTest, QuestionnaireSummaries) {
  const std::string dir = MakeTempDir("analysis_questions");
  PlanOptions o;
  o.clips = {testing::MakeClip(dir, "crane")};
  o.participants = 5;
  o.questionnaire = {
      {"comfort", "Comfortable?", "likert", 1, 5, "", "", {}},
      {"metaphor", "Recognised a motion?", "choice", 1, 5, "", "", {"yes", "no", "not sure"}},
      {"comments", "Comments?", "text", 1, 5, "", "", {}}};
  const StudyPlan plan = MakePlan(o, nullptr);
  std::vector<ParticipantResults> results = Synthesize(plan);
  const std::vector<int> comfort = {5, 1, 4, 2, 4};
  const std::vector<std::string> metaphor = {"yes", "no", "yes", "yes", "not sure"};
  const std::vector<std::string> comments = {"crab walk", "", "", "flying away", ""};
  for (size_t p = 0; p < results.size(); ++p) {
    results[p].questionnaire = {{o.questionnaire[0], comfort[p], "t"},
                                {o.questionnaire[1], metaphor[p], "t"},
                                {o.questionnaire[2], comments[p], "t"}};
    // Through the file format, as analyze reads it.
    results[p] = ResultsFromJson(ResultsToJson(results[p]), results[p].source);
  }
  const StudyAnalysis a = AnalyzeStudy(results);
  ASSERT_EQ(a.questionnaire.size(), 3u);
  const QuestionSummary& c = a.questionnaire[0];
  EXPECT_EQ(c.n, 5);
  ASSERT_GE(c.likert.size(), 2u);
  EXPECT_EQ(c.likert[0].group, "all");
  EXPECT_DOUBLE_EQ(c.likert[0].median, 4);  // sorted 1 2 4 4 5
  EXPECT_DOUBLE_EQ(c.likert[0].mean, 3.2);
  EXPECT_DOUBLE_EQ(c.likert[0].q1, 2);
  EXPECT_DOUBLE_EQ(c.likert[0].q3, 4);
  int by_training = 0;
  for (size_t g = 1; g < c.likert.size(); ++g) by_training += c.likert[g].n;
  EXPECT_EQ(by_training, 5);
  EXPECT_EQ(a.questionnaire[1].n, 5);
  EXPECT_EQ(a.questionnaire[1].counts,
            (std::vector<std::pair<std::string, int>>{{"yes", 3}, {"no", 1}, {"not sure", 1}}));
  EXPECT_EQ(a.questionnaire[2].n, 2);
  EXPECT_EQ(a.questionnaire[2].texts, (std::vector<std::string>{"crab walk", "flying away"}));

  const std::string text = FormatReport(a);
  EXPECT_NE(text.find("comfort (likert 1-5): Comfortable?"), std::string::npos) << text;
  EXPECT_NE(text.find("n=5   median 4.0   mean 3.20   IQR 2.00-4.00 (2.00)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("n=5:  yes 3  no 1  not sure 1"), std::string::npos) << text;
  EXPECT_NE(text.find("n=2 non-empty answers"), std::string::npos) << text;
  const nlohmann::json j = ReportToJson(a);
  ASSERT_EQ(j["questionnaire"].size(), 3u);
  EXPECT_EQ(j["questionnaire"][0]["likert"][0]["iqr"], 2.0);
  EXPECT_EQ(j["questionnaire"][0]["likert"][0]["median"], 4.0);
  EXPECT_EQ(j["questionnaire"][1]["counts"]["yes"], 3);
  EXPECT_EQ(j["questionnaire"][2]["n"], 2);

  // Files of one plan must hold the same questions.
  std::vector<ParticipantResults> missing = results;
  missing[2].questionnaire.clear();
  try {
    AnalyzeStudy(missing);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              missing[2].source + ": questionnaire differs from " + missing[0].source);
  }

  // One answer that does not fit its question is refused when the file is read.
  nlohmann::json bad = ResultsToJson(results[0]);
  bad["questionnaire"][0]["answer"] = 6;
  EXPECT_THROW(ResultsFromJson(bad, "P01.results.json"), Error);
}

TEST(AnalysisTest, LikertSummaryOfOneAnswer) {
  const LikertSummary s = SummariseLikert("all", {3});
  EXPECT_EQ(s.n, 1);
  EXPECT_DOUBLE_EQ(s.median, 3);
  EXPECT_DOUBLE_EQ(s.q1, 3);
  EXPECT_DOUBLE_EQ(s.q3, 3);
}

}  // namespace
}  // namespace hapcine::study
