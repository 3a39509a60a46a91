#include "study/analysis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.h"

namespace hapcine::study {
namespace {

// Whether conditions a and b are in one group (one stimulus) of `clip`.
bool SameStimulus(const ParticipantResults& r, const std::string& clip, const std::string& a,
                  const std::string& b) {
  for (const auto& c : r.clips) {
    if (c.name != clip) continue;
    for (const auto& g : c.groups) {
      const bool has_a = std::find(g.begin(), g.end(), a) != g.end();
      const bool has_b = std::find(g.begin(), g.end(), b) != g.end();
      if (has_a || has_b) return has_a && has_b;
    }
  }
  return false;
}

ScoreTable Score(const std::string& label, const std::vector<ParticipantResults>& results,
                 const std::vector<std::string>& conditions, const std::string* only_clip) {
  ScoreTable t;
  t.label = label;
  const size_t k = conditions.size();
  std::map<std::string, size_t> col;
  for (size_t c = 0; c < k; ++c) col[conditions[c]] = c;
  for (const auto& r : results) {
    std::vector<double> points(k, 0.0), max_points(k, 0.0);
    for (const auto& tr : r.trials) {
      if (only_clip && tr.clip != *only_clip) continue;
      for (const auto& c : tr.first) max_points[col.at(c)] += 1;
      for (const auto& c : tr.second) max_points[col.at(c)] += 1;
      for (const auto& c : tr.chosen()) points[col.at(c)] += 1;
    }
    std::vector<double> s(k);
    for (size_t c = 0; c < k; ++c) s[c] = max_points[c] > 0 ? points[c] / max_points[c] : 0;
    t.score.push_back(s);
  }
  const size_t n = t.score.size();
  t.mean.assign(k, 0);
  t.sd.assign(k, 0);
  for (size_t c = 0; c < k; ++c) {
    std::vector<double> col_scores;
    for (size_t p = 0; p < n; ++p) col_scores.push_back(t.score[p][c]);
    double m = 0;
    for (double v : col_scores) m += v;
    m /= n;
    double ss = 0;
    for (double v : col_scores) ss += (v - m) * (v - m);
    t.mean[c] = m;
    t.sd[c] = n > 1 ? std::sqrt(ss / (n - 1)) : 0;
    t.normality.push_back(ShapiroWilk(col_scores));
  }
  t.friedman = FriedmanTest(t.score);
  // Holm's family: the pairs actually tested (a merged pair is one stimulus).
  std::vector<double> raw;
  std::vector<size_t> tested;
  for (size_t a = 0; a < k; ++a)
    for (size_t b = a + 1; b < k; ++b) {
      PairwiseTest pt;
      pt.a = conditions[a];
      pt.b = conditions[b];
      pt.same_stimulus =
          only_clip && SameStimulus(results.front(), *only_clip, conditions[a], conditions[b]);
      std::vector<double> x, y;
      for (size_t p = 0; p < n; ++p) {
        x.push_back(t.score[p][a]);
        y.push_back(t.score[p][b]);
      }
      pt.wilcoxon = WilcoxonSignedRank(x, y);
      if (!pt.same_stimulus) {
        raw.push_back(pt.wilcoxon.valid ? pt.wilcoxon.p : 1.0);
        tested.push_back(t.pairwise.size());
      }
      t.pairwise.push_back(pt);
    }
  const auto adj = HolmAdjust(raw);
  for (size_t i = 0; i < adj.size(); ++i) t.pairwise[tested[i]].p_holm = adj[i];
  return t;
}

double Quantile(const std::vector<double>& sorted, double p) {
  const double h = (sorted.size() - 1) * p;
  const size_t lo = static_cast<size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  return sorted[lo] + (h - lo) * (sorted[lo + 1] - sorted[lo]);
}

QuestionSummary SummariseQuestion(const std::vector<ParticipantResults>& results, size_t qi,
                                  const std::vector<std::string>& conditions) {
  QuestionSummary s;
  s.question = results.front().questionnaire[qi].question;
  std::vector<double> all;
  std::map<std::string, std::vector<double>> by_training;
  for (const auto& o : s.question.options) s.counts.push_back({o, 0});
  for (const auto& r : results) {
    const nlohmann::json& answer = r.questionnaire[qi].answer;
    if (s.question.type == "likert") {
      all.push_back(answer.get<int>());
      by_training[r.training_condition].push_back(answer.get<int>());
    } else if (s.question.type == "choice") {
      for (auto& [option, count] : s.counts) count += option == answer.get<std::string>();
    } else if (!answer.get<std::string>().empty()) {
      s.texts.push_back(answer.get<std::string>());
    }
  }
  s.n = s.question.type == "text" ? static_cast<int>(s.texts.size())
                                  : static_cast<int>(results.size());
  if (s.question.type == "likert") {
    s.likert.push_back(SummariseLikert("all", all));
    for (const auto& c : conditions)
      if (by_training.count(c)) s.likert.push_back(SummariseLikert(c, by_training[c]));
  }
  return s;
}

std::vector<QuestionSummary> SummariseQuestionnaire(const std::vector<ParticipantResults>& results,
                                                    const std::vector<std::string>& conditions) {
  const ParticipantResults& first = results.front();
  for (const auto& r : results) {
    bool same = r.questionnaire.size() == first.questionnaire.size();
    for (size_t i = 0; same && i < r.questionnaire.size(); ++i)
      same = r.questionnaire[i].question.id == first.questionnaire[i].question.id;
    if (!same) throw Error(r.source, "questionnaire differs from " + first.source);
  }
  std::vector<QuestionSummary> out;
  for (size_t i = 0; i < first.questionnaire.size(); ++i)
    out.push_back(SummariseQuestion(results, i, conditions));
  return out;
}

}  // namespace

LikertSummary SummariseLikert(const std::string& group, std::vector<double> values) {
  LikertSummary s;
  s.group = group;
  s.n = static_cast<int>(values.size());
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / values.size();
  s.median = Quantile(values, 0.5);
  s.q1 = Quantile(values, 0.25);
  s.q3 = Quantile(values, 0.75);
  return s;
}

StudyAnalysis AnalyzeStudy(const std::vector<ParticipantResults>& results) {
  if (results.empty()) throw UsageError("no results files given");
  const ParticipantResults& first = results.front();
  StudyAnalysis a;
  a.plan_id = first.plan_id;
  a.conditions = first.conditions;
  for (const auto& c : first.clips) a.clips.push_back(c.name);
  std::set<std::string> seen;
  for (const auto& r : results) {
    if (r.plan_id != first.plan_id)
      throw Error(r.source, "results of plan " + r.plan_id + ", but " + first.source +
                                " is of plan " + first.plan_id + ": plans cannot be mixed");
    if (r.conditions != first.conditions)
      throw Error(r.source, "conditions differ from " + first.source);
    bool same_clips = r.clips.size() == first.clips.size();
    for (size_t i = 0; same_clips && i < r.clips.size(); ++i)
      same_clips =
          r.clips[i].name == first.clips[i].name && r.clips[i].groups == first.clips[i].groups;
    if (!same_clips)
      throw Error(r.source, "clips differ from " + first.source + " under the same plan id");
    if (!seen.insert(r.participant).second)
      throw Error(r.source, "participant " + r.participant + " appears in two results files");
    a.participants.push_back(r.participant);
  }
  a.overall = Score("all", results, a.conditions, nullptr);
  for (const auto& c : a.clips) a.per_clip.push_back(Score(c, results, a.conditions, &c));
  a.questionnaire = SummariseQuestionnaire(results, a.conditions);
  return a;
}

}  // namespace hapcine::study
