#include "study/questionnaire.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "study/json_util.h"
#include "study/plan.h"
#include "study/test_fixtures.h"

namespace hapcine::study {
namespace {
using nlohmann::json;
using testing::MakeClip;
using testing::MakeTempDir;

StudyPlan SmallPlan(const std::string& dir, const std::vector<Question>& questionnaire) {
  PlanOptions o;
  o.clips = {MakeClip(dir, "crane")};
  o.participants = 2;
  o.questionnaire = questionnaire;
  return MakePlan(o, nullptr);
}

// The message of loading `plan_json` from `path`, or "" if it loaded.
std::string LoadError(const json& plan_json, const std::string& path) {
  std::ofstream(path) << plan_json.dump(1);
  try {
    ReadPlanFile(path);
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

TEST(QuestionnaireTest, PlanWithoutQuestionnaireIsUnchanged) {
  const std::string dir = MakeTempDir("q_none");
  const StudyPlan plain = SmallPlan(dir, {});
  const json j = PlanToJson(plain);
  EXPECT_FALSE(j.contains("questionnaire"));  // so the plan id is the one made before
  WritePlanFile(plain, dir + "/plain.json");
  EXPECT_TRUE(ReadPlanFile(dir + "/plain.json").questionnaire.empty());

  const StudyPlan asked = SmallPlan(dir, PaperQuestionnaire());
  EXPECT_NE(asked.plan_id, plain.plan_id);
  WritePlanFile(asked, dir + "/asked.json");
  const StudyPlan back = ReadPlanFile(dir + "/asked.json");
  ASSERT_EQ(back.questionnaire.size(), PaperQuestionnaire().size());
  EXPECT_EQ(QuestionnaireToJson(back.questionnaire), QuestionnaireToJson(PaperQuestionnaire()));
  EXPECT_EQ(back.plan_id, asked.plan_id);
}

TEST(QuestionnaireTest, BadQuestionsAreOneLineErrorsNamingPlanAndQuestion) {
  const std::string dir = MakeTempDir("q_bad");
  const json good = PlanToJson(SmallPlan(dir, PaperQuestionnaire()));
  const std::string path = dir + "/plan.json";
  ASSERT_EQ(LoadError(good, path), "");
  struct Case {
    json question;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{{"id", "q1"}, {"text", "How?"}, {"type", "scale"}},
       "questionnaire question 'q1': type must be likert, choice or text, got 'scale'"},
      {{{"id", "q1"}, {"text", "How?"}, {"type", "likert"}, {"min", 5}, {"max", 5}},
       "questionnaire question 'q1': min (5) must be below max (5)"},
      {{{"id", "q1"}, {"text", "How?"}, {"type", "likert"}, {"min", 7}, {"max", 1}},
       "questionnaire question 'q1': min (7) must be below max (1)"},
      {{{"id", "q1"}, {"text", "How?"}, {"type", "likert"}, {"min", 1}},
       "questionnaire question 'q1': missing field 'max'"},
      {{{"id", "q1"}, {"text", "Which?"}, {"type", "choice"}, {"options", {"yes"}}},
       "questionnaire question 'q1': a choice needs at least two options"},
      {{{"id", "q1"}, {"text", "Which?"}, {"type", "choice"}, {"options", {"yes", "Yes"}}},
       "questionnaire question 'q1': option 'Yes' listed twice"},
      {{{"id", "q1"}, {"text", " "}, {"type", "text"}}, "questionnaire question 'q1': empty text"},
      {{{"id", "enjoyed"}, {"text", "Again?"}, {"type", "text"}},
       "questionnaire question 'enjoyed': id used twice"},
  };
  for (const Case& c : cases) {
    json edited = good;
    edited["questionnaire"].push_back(c.question);
    EXPECT_EQ(LoadError(edited, path), path + ": " + c.message) << c.question.dump();
  }
  json not_array = good;
  not_array["questionnaire"] = "enjoyed";
  EXPECT_EQ(LoadError(not_array, path), path + ": questionnaire must be an array of questions");
}

TEST(QuestionnaireTest, QuestionnaireFileForThePlanCommand) {
  const std::string dir = MakeTempDir("q_file");
  std::ofstream(dir + "/q.json") << R"({"questionnaire": [
      {"id": "fun", "text": "Fun?", "type": "likert", "min": 0, "max": 10, "min_label": "no"}]})";
  const std::vector<Question> qs = ReadQuestionnaireFile(dir + "/q.json");
  ASSERT_EQ(qs.size(), 1u);
  EXPECT_EQ(qs[0].max, 10);
  EXPECT_EQ(qs[0].min_label, "no");
  EXPECT_EQ(qs[0].max_label, "");
  std::ofstream(dir + "/bad.json") << R"([{"id": "fun", "type": "text"}])";
  try {
    ReadQuestionnaireFile(dir + "/bad.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir + "/bad.json: questionnaire question 'fun': missing field 'text'");
  }
}

TEST(QuestionnaireTest, TypedAnswersAreCheckedByType) {
  const std::vector<Question> qs = PaperQuestionnaire();
  const Question& likert = qs[0];  // 1..5
  const Question& choice = qs[4];  // yes / no / not sure
  const Question& text = qs[5];
  std::string why;
  EXPECT_EQ(*ParseAnswer(likert, " 4 ", &why), json(4));
  EXPECT_EQ(*ParseAnswer(likert, "1", &why), json(1));
  for (const char* bad : {"0", "6", "3.5", "", "four", "-", "99999999999"})
    EXPECT_FALSE(ParseAnswer(likert, bad, &why)) << bad;
  EXPECT_EQ(why, "Please type a whole number from 1 to 5.");
  EXPECT_EQ(*ParseAnswer(choice, "3", &why), json("not sure"));
  EXPECT_EQ(*ParseAnswer(choice, "YES", &why), json("yes"));
  EXPECT_FALSE(ParseAnswer(choice, "4", &why));
  EXPECT_FALSE(ParseAnswer(choice, "maybe", &why));
  EXPECT_EQ(*ParseAnswer(text, "  like a crab walk ", &why), json("like a crab walk"));
  EXPECT_EQ(*ParseAnswer(text, "", &why), json(""));

  EXPECT_TRUE(AnswerValid(likert, json(5)));
  EXPECT_FALSE(AnswerValid(likert, json(6)));
  EXPECT_FALSE(AnswerValid(likert, json("5")));
  EXPECT_FALSE(AnswerValid(likert, json(4.5)));
  EXPECT_TRUE(AnswerValid(choice, json("no")));
  EXPECT_FALSE(AnswerValid(choice, json("No")));
  EXPECT_FALSE(AnswerValid(text, json(3)));
}

}  // namespace
}  // namespace hapcine::study
