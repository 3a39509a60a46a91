#include "study/questionnaire.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "core/error.h"
#include "core/text.h"
#include "study/json_util.h"

namespace hapcine::study {
using nlohmann::json;

std::vector<Question> PaperQuestionnaire() {
  const std::string disagree = "strongly disagree", agree = "strongly agree";
  std::vector<Question> qs;
  qs.push_back({"enjoyed",
                "The haptic feedback made the videos more enjoyable.",
                "likert",
                1,
                5,
                disagree,
                agree,
                {}});
  qs.push_back({"matched_camera",
                "The movements of the seat matched the motion of the camera.",
                "likert",
                1,
                5,
                disagree,
                agree,
                {}});
  qs.push_back({"easy_to_interpret",
                "The movements of the seat were easy to interpret.",
                "likert",
                1,
                5,
                disagree,
                agree,
                {}});
  qs.push_back({"comfortable",
                "The movements of the seat were comfortable.",
                "likert",
                1,
                5,
                disagree,
                agree,
                {}});
  qs.push_back({"recognised_metaphor",
                "Did some movements remind you of a familiar motion (walking, a crab walk, flying "
                "away...)?",
                "choice",
                1,
                5,
                "",
                "",
                {"yes", "no", "not sure"}});
  qs.push_back({"metaphor_description",
                "If so, which motion, and in which video?",
                "text",
                1,
                5,
                "",
                "",
                {}});
  qs.push_back({"best_suited",
                "Where would such effects suit you best?",
                "choice",
                1,
                5,
                "",
                "",
                {"films", "first-person videos", "video games", "nowhere"}});
  qs.push_back({"comments", "Any other comments on your experience?", "text", 1, 5, "", "", {}});
  return qs;
}

namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

Question QuestionFromJson(const json& jq, size_t position, const std::string& src) {
  const std::string at = "questionnaire question " + std::to_string(position + 1);
  if (!jq.is_object()) throw Error(src, at + ": not an object");
  Question q;
  q.id = StringField(jq, "id", src, at);
  const std::string where = "questionnaire question '" + q.id + "'";
  if (q.id.empty()) throw Error(src, at + ": empty id");
  q.text = StringField(jq, "text", src, where);
  if (Trim(q.text).empty()) throw Error(src, where + ": empty text");
  q.type = StringField(jq, "type", src, where);
  if (q.type == "likert") {
    q.min = IntField(jq, "min", src, where);
    q.max = IntField(jq, "max", src, where);
    if (q.min >= q.max)
      throw Error(src, where + ": min (" + std::to_string(q.min) + ") must be below max (" +
                           std::to_string(q.max) + ")");
    if (q.max - q.min > 100) throw Error(src, where + ": more than 101 scale points");
    if (jq.contains("min_label")) q.min_label = StringField(jq, "min_label", src, where);
    if (jq.contains("max_label")) q.max_label = StringField(jq, "max_label", src, where);
  } else if (q.type == "choice") {
    q.options = StringArray(ArrayField(jq, "options", src, where), src, where + " options");
    std::set<std::string> seen;
    for (const auto& o : q.options) {
      if (Trim(o).empty()) throw Error(src, where + ": empty option");
      if (!seen.insert(LowerCase(o)).second)
        throw Error(src, where + ": option '" + o + "' listed twice");
    }
    if (q.options.size() < 2) throw Error(src, where + ": a choice needs at least two options");
  } else if (q.type != "text") {
    throw Error(src, where + ": type must be likert, choice or text, got '" + q.type + "'");
  }
  return q;
}

}  // namespace

std::vector<Question> QuestionnaireFromJson(const json& j, const std::string& src) {
  if (!j.is_array()) throw Error(src, "questionnaire must be an array of questions");
  std::vector<Question> qs;
  std::set<std::string> ids;
  for (size_t i = 0; i < j.size(); ++i) {
    qs.push_back(QuestionFromJson(j[i], i, src));
    if (!ids.insert(qs.back().id).second)
      throw Error(src, "questionnaire question '" + qs.back().id + "': id used twice");
  }
  return qs;
}

json QuestionToJson(const Question& q) {
  json j = {{"id", q.id}, {"text", q.text}, {"type", q.type}};
  if (q.type == "likert") {
    j["min"] = q.min;
    j["max"] = q.max;
    if (!q.min_label.empty()) j["min_label"] = q.min_label;
    if (!q.max_label.empty()) j["max_label"] = q.max_label;
  } else if (q.type == "choice") {
    j["options"] = q.options;
  }
  return j;
}

json QuestionnaireToJson(const std::vector<Question>& qs) {
  json j = json::array();
  for (const auto& q : qs) j.push_back(QuestionToJson(q));
  return j;
}

std::vector<Question> ReadQuestionnaireFile(const std::string& path) {
  const json j = ReadJsonFile(path);
  return QuestionnaireFromJson(j.is_object() ? Field(j, "questionnaire", path, "file") : j, path);
}

std::string QuestionPrompt(const Question& q) {
  std::string s = q.text + "\n";
  if (q.type == "likert") {
    s += "  Type a number from " + std::to_string(q.min);
    if (!q.min_label.empty()) s += " (" + q.min_label + ")";
    s += " to " + std::to_string(q.max);
    if (!q.max_label.empty()) s += " (" + q.max_label + ")";
    s += ":";
  } else if (q.type == "choice") {
    for (size_t i = 0; i < q.options.size(); ++i)
      s += "  " + std::to_string(i + 1) + ") " + q.options[i] + "\n";
    s += "  Type the number of your answer:";
  } else {
    s += "  Type your answer on one line (Enter alone for none):";
  }
  return s + " ";
}

std::optional<json> ParseAnswer(const Question& q, const std::string& typed, std::string* why) {
  const std::string t = Trim(typed);
  if (q.type == "text") return json(t);
  if (q.type == "likert") {
    const bool digits = !t.empty() && t.size() <= 4 &&
                        std::all_of(t.begin() + (t[0] == '-' && t.size() > 1), t.end(),
                                    [](unsigned char c) { return std::isdigit(c); });
    if (digits) {
      const int v = std::stoi(t);
      if (v >= q.min && v <= q.max) return json(v);
    }
    *why = "Please type a whole number from " + std::to_string(q.min) + " to " +
           std::to_string(q.max) + ".";
    return std::nullopt;
  }
  for (size_t i = 0; i < q.options.size(); ++i)
    if (t == std::to_string(i + 1) || LowerCase(t) == LowerCase(q.options[i])) return json(q.options[i]);
  *why = "Please type a number from 1 to " + std::to_string(q.options.size()) + ".";
  return std::nullopt;
}

bool AnswerValid(const Question& q, const json& a) {
  if (q.type == "likert")
    return a.is_number_integer() && a.get<int>() >= q.min && a.get<int>() <= q.max;
  if (q.type == "choice")
    return a.is_string() &&
           std::find(q.options.begin(), q.options.end(), a.get<std::string>()) != q.options.end();
  return a.is_string();
}

}  // namespace hapcine::study
