#pragma once
// Scores and tests of the pairwise study (paper, section 5.3). A point goes
// to a condition each time a participant prefers a stimulus it belongs to;
// a condition's score is its points divided by the number of trials it
// appeared in (its maximum possible), so every score is in [0, 1]. Scores
// are computed per participant, over all clips and per clip (sequence).
//
// Tests, participants as the unit of observation:
//   * Shapiro–Wilk on each condition's scores (is a parametric test allowed?);
//   * Friedman across conditions, participants as blocks;
//   * Wilcoxon signed-rank for every pair of conditions, p-values adjusted
//     with Holm–Bonferroni within each family (overall; each clip).

#include <string>
#include <vector>

#include "study/results.h"
#include "study/stats.h"

namespace hapcine::study {

struct PairwiseTest {
  std::string a, b;  // conditions
  WilcoxonResult wilcoxon;
  double p_holm = 1;  // Holm-adjusted within its family
  // The two conditions are one stimulus on this clip (identical tracks,
  // merged by the plan, e.g. the paper's Vertigo): not a hypothesis, so not
  // tested and not counted in the Holm family (p = p_holm = 1).
  bool same_stimulus = false;
};

// Scores and tests for one set of trials (all clips, or one clip).
struct ScoreTable {
  std::string label;                         // "all" or the clip name
  std::vector<std::vector<double>> score;    // [participant][condition], in [0,1]
  std::vector<double> mean, sd;              // per condition across participants (sd: n-1)
  std::vector<ShapiroWilkResult> normality;  // per condition
  FriedmanResult friedman;
  std::vector<PairwiseTest> pairwise;  // every unordered pair, in condition order
};

// A likert question's answers over a set of participants: all of them, or
// those of one training condition (the condition a participant first met).
struct LikertSummary {
  std::string group;  // "all" or the training condition
  int n = 0;
  double median = 0, mean = 0;
  double q1 = 0, q3 = 0;  // quartiles, linear interpolation (R type 7); IQR = q3 - q1
};

// One post-test question over every participant.
struct QuestionSummary {
  Question question;
  int n = 0;                          // answers; for text, the non-empty ones
  std::vector<LikertSummary> likert;  // likert: "all" first, then each training condition
  std::vector<std::pair<std::string, int>> counts;  // choice: per option, in option order
  std::vector<std::string> texts;                   // text: the non-empty answers
};

struct StudyAnalysis {
  std::string plan_id;
  std::vector<std::string> conditions;
  std::vector<std::string> clips;
  std::vector<std::string> participants;
  ScoreTable overall;
  std::vector<ScoreTable> per_clip;            // in clips order
  std::vector<QuestionSummary> questionnaire;  // in plan order; empty if the plan has none
};

// Median, mean and quartiles of `values` (non-empty).
LikertSummary SummariseLikert(const std::string& group, std::vector<double> values);

// Checks that all results come from one plan (Error naming the first file
// that differs) and have distinct participants, then scores and tests, and
// summarises the questionnaire.
StudyAnalysis AnalyzeStudy(const std::vector<ParticipantResults>& results);

}  // namespace hapcine::study
