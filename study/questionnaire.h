#pragma once
// The post-test questionnaire (paper, section 5.2: "Finally a post-test
// questionnaire was submitted to collect more information about the user's
// experience"). Questions live in the plan (`questionnaire`), are asked by
// `study run` after the last trial, journalled one answer at a time, copied
// with their answers into the results file and summarised by `analyze`.
//
// Question types:
//   likert  an integer in [min, max] (min < max), optional min_label/max_label
//   choice  one of `options` (at least two, distinct); typed as its number or text
//   text    free text (may be empty)

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace hapcine::study {

struct Question {
  std::string id;
  std::string text;
  std::string type;                  // "likert", "choice" or "text"
  int min = 1, max = 5;              // likert
  std::string min_label, max_label;  // likert, optional
  std::vector<std::string> options;  // choice
};

// The questions `study plan --questionnaire paper` puts in a plan. The paper
// does not print its items; these ask what its section 6 reports participants
// said (recognised metaphors, ease of interpretation, fit with the camera
// motion, comfort, where such effects would work).
std::vector<Question> PaperQuestionnaire();

// Parses and validates a questionnaire array. Error(source, "questionnaire
// question '<id>': <reason>") on a bad question, a duplicate id, etc.
std::vector<Question> QuestionnaireFromJson(const nlohmann::json& j, const std::string& source);
nlohmann::json QuestionToJson(const Question& q);
nlohmann::json QuestionnaireToJson(const std::vector<Question>& qs);
// A file holding a questionnaire array, or an object with a `questionnaire` key.
std::vector<Question> ReadQuestionnaireFile(const std::string& path);

// The prompt shown before an answer is typed (question, scale or options).
std::string QuestionPrompt(const Question& q);
// What a typed answer records: likert -> integer, choice -> the option's text
// (typed as its number or its text, case-insensitive), text -> the trimmed
// line. nullopt when invalid; `why` then says what is expected.
std::optional<nlohmann::json> ParseAnswer(const Question& q, const std::string& typed,
                                          std::string* why);
// Whether a recorded answer (journal, results file) is valid for q.
bool AnswerValid(const Question& q, const nlohmann::json& answer);

}  // namespace hapcine::study
