#include "study/results.h"

#include <cmath>
#include <map>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "study/json_util.h"

namespace hapcine::study {
using nlohmann::json;

namespace {
const char* const kFormat = "hapcine-study-results";
constexpr int kVersion = 1;

// The optional `questionnaire` array: questions as in the plan, each with
// its answer.
std::vector<QuestionAnswer> QuestionnaireAnswers(const json& j, const std::string& src) {
  std::vector<QuestionAnswer> out;
  if (!j.contains("questionnaire")) return out;
  const std::vector<Question> qs = QuestionnaireFromJson(j["questionnaire"], src);
  for (size_t i = 0; i < qs.size(); ++i) {
    const std::string where = "questionnaire question '" + qs[i].id + "'";
    QuestionAnswer qa{qs[i], Field(j["questionnaire"][i], "answer", src, where),
                      StringField(j["questionnaire"][i], "answered_utc", src, where)};
    if (!AnswerValid(qa.question, qa.answer))
      throw Error(src, where + ": answer " + qa.answer.dump() + " does not fit the question");
    out.push_back(std::move(qa));
  }
  return out;
}

std::string Key(const std::string& clip, const std::vector<std::string>& a,
                const std::vector<std::string>& b) {
  return clip + "|" + json(a).dump() + "|" + json(b).dump();
}
}  // namespace

json ResultsToJson(const ParticipantResults& r) {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["plan_id"] = r.plan_id;
  j["participant"] = r.participant;
  j["device"] = r.device;
  j["conditions"] = r.conditions;
  j["clips"] = json::array();
  for (const auto& c : r.clips) j["clips"].push_back({{"name", c.name}, {"groups", c.groups}});
  j["training_condition"] = r.training_condition;
  j["started_utc"] = r.started_utc;
  j["completed_utc"] = r.completed_utc;
  j["trials"] = json::array();
  for (const auto& t : r.trials)
    j["trials"].push_back({{"index", t.index},
                           {"clip", t.clip},
                           {"first", t.first},
                           {"second", t.second},
                           {"choice", t.choice},
                           {"response_time_s", t.response_time_s},
                           {"answered_utc", t.answered_utc}});
  if (!r.questionnaire.empty()) {
    j["questionnaire"] = json::array();
    for (const auto& qa : r.questionnaire) {
      json jq = QuestionToJson(qa.question);
      jq["answer"] = qa.answer;
      jq["answered_utc"] = qa.answered_utc;
      j["questionnaire"].push_back(jq);
    }
  }
  return j;
}

void WriteResultsFile(const ParticipantResults& r, const std::string& path) {
  AtomicFile out(path);
  out.stream() << ResultsToJson(r).dump(1) << "\n";
  out.Commit();
}

namespace {

// One clip of the design: its groups of conditions, which must partition
// `conds`.
ClipGroups ClipFromJson(const json& jc, const std::set<std::string>& conds,
                        const std::string& src) {
  ClipGroups c;
  c.name = StringField(jc, "name", src, "clip");
  std::set<std::string> covered;
  for (const auto& g : ArrayField(jc, "groups", src, "clip '" + c.name + "'")) {
    c.groups.push_back(StringArray(g, src, "clip '" + c.name + "' groups"));
    if (c.groups.back().empty()) throw Error(src, "clip '" + c.name + "' has an empty group");
    for (const auto& cond : c.groups.back()) {
      if (!conds.count(cond))
        throw Error(src, "clip '" + c.name + "': unknown condition '" + cond + "'");
      if (!covered.insert(cond).second)
        throw Error(src, "clip '" + c.name + "': condition '" + cond + "' in two groups");
    }
  }
  if (covered.size() != conds.size())
    throw Error(src, "clip '" + c.name + "': groups do not cover every condition");
  return c;
}

// One recorded trial, its fields checked (not yet against the design).
TrialResult TrialFromJson(const json& t, const std::string& src) {
  TrialResult tr;
  tr.index = IntField(t, "index", src, "trial");
  const std::string where = "trial " + std::to_string(tr.index);
  tr.clip = StringField(t, "clip", src, where);
  tr.first = StringArray(Field(t, "first", src, where), src, where + " first");
  tr.second = StringArray(Field(t, "second", src, where), src, where + " second");
  tr.choice = IntField(t, "choice", src, where);
  if (tr.choice != 1 && tr.choice != 2)
    throw Error(src, where + ": choice must be 1 or 2, got " + std::to_string(tr.choice));
  tr.response_time_s = NumberField(t, "response_time_s", src, where);
  if (tr.response_time_s < 0) throw Error(src, where + ": negative response time");
  tr.answered_utc = StringField(t, "answered_utc", src, where);
  return tr;
}

// The design's clips; `expected` gets every ordered pair of distinct groups
// of every clip (key -> times seen, 0).
std::vector<ClipGroups> ClipsFromJson(const json& j, const std::set<std::string>& conds,
                                      const std::string& src,
                                      std::map<std::string, int>* expected) {
  std::vector<ClipGroups> clips;
  std::set<std::string> clip_names;
  for (const auto& jc : ArrayField(j, "clips", src, "results")) {
    ClipGroups c = ClipFromJson(jc, conds, src);
    if (!clip_names.insert(c.name).second) throw Error(src, "clip '" + c.name + "' listed twice");
    for (size_t a = 0; a < c.groups.size(); ++a)
      for (size_t b = 0; b < c.groups.size(); ++b)
        if (a != b) (*expected)[Key(c.name, c.groups[a], c.groups[b])] = 0;
    clips.push_back(std::move(c));
  }
  if (clips.empty()) throw Error(src, "no clips");
  return clips;
}

// The trials, each a pair of the design presented once, all of it, indexed
// 0..n-1.
std::vector<TrialResult> TrialsFromJson(const json& j, const std::string& src,
                                        std::map<std::string, int> expected) {
  const json& jt = ArrayField(j, "trials", src, "results");
  std::vector<TrialResult> trials;
  std::set<int> indices;
  for (const auto& t : jt) {
    TrialResult tr = TrialFromJson(t, src);
    const std::string where = "trial " + std::to_string(tr.index);
    if (!indices.insert(tr.index).second) throw Error(src, where + " recorded twice");
    const auto it = expected.find(Key(tr.clip, tr.first, tr.second));
    if (it == expected.end())
      throw Error(src, where + ": pair is not part of the design (clip '" + tr.clip + "')");
    if (++it->second > 1) throw Error(src, where + ": pair presented twice");
    trials.push_back(std::move(tr));
  }
  for (const auto& [key, seen] : expected)
    if (seen == 0)
      throw Error(src, "incomplete: " + std::to_string(expected.size()) + " trials expected, " +
                           std::to_string(jt.size()) + " recorded");
  for (int i = 0; i < static_cast<int>(trials.size()); ++i)
    if (!indices.count(i))
      throw Error(src, "trial indices are not 0.." + std::to_string(trials.size() - 1));
  return trials;
}

}  // namespace

ParticipantResults ResultsFromJson(const json& j, const std::string& src) {
  if (!j.is_object() || !j.contains("format") || j["format"] != kFormat)
    throw Error(src, "not a hapcine study results file (format field is not '" +
                         std::string(kFormat) + "')");
  if (IntField(j, "version", src, "results") != kVersion)
    throw Error(src, "unsupported results version " + j["version"].dump());
  ParticipantResults r;
  r.source = src;
  r.plan_id = StringField(j, "plan_id", src, "results");
  r.participant = StringField(j, "participant", src, "results");
  r.device = StringField(j, "device", src, "results");
  r.training_condition = StringField(j, "training_condition", src, "results");
  r.started_utc = StringField(j, "started_utc", src, "results");
  r.completed_utc = StringField(j, "completed_utc", src, "results");
  r.conditions = StringArray(ArrayField(j, "conditions", src, "results"), src, "conditions");
  const std::set<std::string> conds(r.conditions.begin(), r.conditions.end());
  if (conds.size() != r.conditions.size() || conds.size() < 2)
    throw Error(src, "conditions must be at least two distinct names");
  if (!conds.count(r.training_condition))
    throw Error(src, "unknown training condition '" + r.training_condition + "'");
  std::map<std::string, int> expected;  // the design: key -> times seen
  r.clips = ClipsFromJson(j, conds, src, &expected);
  r.trials = TrialsFromJson(j, src, std::move(expected));
  r.questionnaire = QuestionnaireAnswers(j, src);
  return r;
}

ParticipantResults ReadResultsFile(const std::string& path) {
  return ResultsFromJson(ReadJsonFile(path), path);
}

}  // namespace hapcine::study
