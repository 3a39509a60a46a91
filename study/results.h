#pragma once
// One participant's answers (`<participant>.results.json`), written by
// `hapcine study run` when the last trial is answered and read by
// `hapcine study analyze`. Self-contained: it repeats the plan id, the
// conditions and each clip's identical-track groups, so the analysis needs
// no other file. See docs/study.md for the layout.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "study/questionnaire.h"

namespace hapcine::study {

struct ClipGroups {
  std::string name;
  std::vector<std::vector<std::string>> groups;
};

struct TrialResult {
  int index = 0;
  std::string clip;
  std::vector<std::string> first, second;
  int choice = 0;              // 1 = first, 2 = second
  double response_time_s = 0;  // from the end of the second stimulus to the answer
  std::string answered_utc;
  const std::vector<std::string>& chosen() const { return choice == 1 ? first : second; }
};

// One post-test question with the participant's answer (an integer for
// likert, the option's text for choice, a string for text).
struct QuestionAnswer {
  Question question;
  nlohmann::json answer;
  std::string answered_utc;
};

struct ParticipantResults {
  std::string source;  // file it was read from (for messages)
  std::string plan_id;
  std::string participant;
  std::string device;
  std::vector<std::string> conditions;
  std::vector<ClipGroups> clips;
  std::string training_condition;
  std::vector<TrialResult> trials;  // by index, every trial exactly once
  std::string started_utc, completed_utc;
  // The plan's questionnaire in plan order, each answered; empty when the
  // plan has none (the `questionnaire` key is then absent from the file).
  std::vector<QuestionAnswer> questionnaire;
};

nlohmann::json ResultsToJson(const ParticipantResults& r);
void WriteResultsFile(const ParticipantResults& r, const std::string& path);  // atomic
// Reads and validates: format and version, every field's type, choices 1/2,
// finite non-negative response times, known clips and conditions, and that
// the trials are exactly the plan's design (each ordered pair of distinct
// groups of each clip once), and every questionnaire answer fits its question. Error(path, reason)
// otherwise.
ParticipantResults ReadResultsFile(const std::string& path);
ParticipantResults ResultsFromJson(const nlohmann::json& j, const std::string& source);

}  // namespace hapcine::study
