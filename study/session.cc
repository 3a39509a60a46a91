#include "study/session.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>

#include "core/error.h"
#include "core/input_file.h"
#include "study/hash.h"
#include "study/journal.h"
#include "study/json_util.h"
#include "study/keypress.h"
#include "study/plan.h"
#include "study/player_process.h"
#include "study/results.h"

namespace hapcine::study {
namespace fs = std::filesystem;
using nlohmann::json;

void RunOptions::Check() const {
  if (plan_path.empty()) throw UsageError("a plan file is needed");
  if (participant.empty()) throw UsageError("--participant is needed");
  if (device != "sim" && device != "none" && device != "falcon")
    throw UsageError("--device must be sim, none or falcon");
}

std::string JournalPathFor(const std::string& results_path) {
  const std::string suffix = ".results.json";
  if (results_path.size() > suffix.size() &&
      results_path.compare(results_path.size() - suffix.size(), suffix.size(), suffix) == 0)
    return results_path.substr(0, results_path.size() - suffix.size()) + ".journal.jsonl";
  return results_path + ".journal.jsonl";
}

namespace {

// Answers from a responses file (scripted runs) or typed on a stream.
class AnswerSource {
 public:
  AnswerSource(const std::string& responses_path, std::istream& in, std::ostream& out)
      : in_(in),
        out_(out),
        scripted_(!responses_path.empty()),
        // A person at a terminal answers with one key press; a pipe or file
        // on stdin gives one answer per line.
        key_press_(!scripted_ && &in == &std::cin && IsTerminal(STDIN_FILENO)),
        path_(responses_path) {
    if (scripted_) {
      InputFile file(responses_path);
      std::ifstream& f = file.stream();
      std::string line;
      int n = 0;
      while (std::getline(f, line)) {
        ++n;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        const auto b = line.find_first_not_of(" \t\r");
        if (b == std::string::npos) continue;
        const auto e = line.find_last_not_of(" \t\r");
        answers_.push_back({line.substr(b, e - b + 1), n});
      }
    }
  }
  bool scripted() const { return scripted_; }
  // A scripted run whose answers are used up stops before playing another pair.
  bool Exhausted() const { return scripted_ && next_ >= answers_.size(); }
  // 1 or 2; 0 = replay requested; nullopt = stop (end of input or "q").
  std::optional<int> Next() {
    if (scripted_) {
      if (next_ >= answers_.size()) return std::nullopt;
      // Checked here, not on loading: the lines after the trials' answers
      // answer the questionnaire.
      const ScriptedAnswer& a = answers_[next_++];
      if (a.text != "1" && a.text != "2")
        throw Error(path_ + ":" + std::to_string(a.line),
                    "answer must be 1 or 2, got '" + a.text + "'");
      return a.text[0] - '0';
    }
    if (key_press_) {
      for (;;) {
        out_ << "Which did you prefer? Press 1 or 2 (r = replay, q = stop for now) " << std::flush;
        const std::optional<char> key = ReadKeyPress(STDIN_FILENO);
        out_ << (key && *key >= ' ' ? std::string(1, *key) : std::string()) << "\n";
        if (!key || *key == 'q' || *key == 'Q' || *key == 3 || *key == 4) return std::nullopt;
        if (*key == '1' || *key == '2') return *key - '0';
        if (*key == 'r' || *key == 'R') return 0;
      }
    }
    for (;;) {
      out_ << "Which did you prefer? [1/2, r = replay, q = stop for now] " << std::flush;
      std::string line;
      if (!std::getline(in_, line)) return std::nullopt;
      const auto b = line.find_first_not_of(" \t\r");
      const std::string tok =
          b == std::string::npos ? "" : line.substr(b, line.find_last_not_of(" \t\r") - b + 1);
      if (tok == "1" || tok == "2") return tok[0] - '0';
      if (tok == "r" || tok == "R") return 0;
      if (tok == "q" || tok == "Q") return std::nullopt;
      out_ << "Please type 1 or 2.\n";
    }
  }
  // One typed line answering a questionnaire question, after showing
  // `prompt` (a line, even at a terminal: answers can be words). nullopt =
  // stop (end of input or responses, or "q" alone).
  std::optional<std::string> NextLine(const std::string& prompt) {
    out_ << prompt << std::flush;
    std::string line;
    if (scripted_) {
      if (next_ >= answers_.size()) {
        out_ << "\n";
        return std::nullopt;
      }
      line = answers_[next_++].text;
      out_ << line << "\n";
    } else if (!std::getline(in_, line)) {
      out_ << "\n";
      return std::nullopt;
    }
    const auto b = line.find_first_not_of(" \t\r");
    const std::string tok =
        b == std::string::npos ? "" : line.substr(b, line.find_last_not_of(" \t\r") - b + 1);
    if (tok == "q" || tok == "Q") return std::nullopt;
    return line;
  }

 private:
  std::istream& in_;
  std::ostream& out_;
  bool scripted_;
  bool key_press_;
  std::string path_;
  struct ScriptedAnswer {
    std::string text;  // trimmed, comment removed
    int line = 0;      // in the responses file
  };
  std::vector<ScriptedAnswer> answers_;
  size_t next_ = 0;
};

// What the journal already holds, each record checked against the plan.
struct JournalState {
  bool training_done = false;
  std::map<int, json> trials;                    // index -> record
  std::map<std::string, json> question_answers;  // question id -> record
};

void ReadTrialRecord(const json& r, const ParticipantPlan& who, const std::string& path,
                     JournalState* state) {
  const std::string where = "journal record";
  const int total = static_cast<int>(who.trials.size());
  const int idx = IntField(r, "index", path, where);
  if (idx < 0 || idx >= total)
    throw Error(path, "trial index " + std::to_string(idx) + " is not in the plan");
  const Trial& t = who.trials[idx];
  if (StringField(r, "clip", path, where) != t.clip ||
      StringArray(Field(r, "first", path, where), path, where) != t.first ||
      StringArray(Field(r, "second", path, where), path, where) != t.second)
    throw Error(path, "trial " + std::to_string(idx) + " does not match the plan");
  const int choice = IntField(r, "choice", path, where);
  if (choice != 1 && choice != 2)
    throw Error(path, "trial " + std::to_string(idx) + ": choice must be 1 or 2");
  NumberField(r, "response_time_s", path, where);
  StringField(r, "answered_utc", path, where);
  if (!state->trials.emplace(idx, r).second)
    throw Error(path, "trial " + std::to_string(idx) + " recorded twice");
}

void ReadAnswerRecord(const json& r, const StudyPlan& plan, const std::string& path,
                      JournalState* state) {
  const std::string id = StringField(r, "id", path, "journal answer");
  const std::string where = "questionnaire question '" + id + "'";
  const auto q = std::find_if(plan.questionnaire.begin(), plan.questionnaire.end(),
                              [&](const Question& x) { return x.id == id; });
  if (q == plan.questionnaire.end()) throw Error(path, where + " is not in the plan");
  if (!AnswerValid(*q, Field(r, "answer", path, where)))
    throw Error(path, where + ": answer " + r["answer"].dump() + " does not fit the question");
  StringField(r, "answered_utc", path, where);
  if (!state->question_answers.emplace(id, r).second) throw Error(path, where + " answered twice");
}

JournalState ReadJournalState(const Journal& journal, const StudyPlan& plan,
                              const ParticipantPlan& who) {
  JournalState state;
  for (const auto& r : journal.records()) {
    const std::string type = StringField(r, "type", journal.path(), "journal record");
    if (type == "training_done") {
      state.training_done = true;
    } else if (type == "trial") {
      ReadTrialRecord(r, who, journal.path(), &state);
    } else if (type == "answer") {
      ReadAnswerRecord(r, plan, journal.path(), &state);
    } else if (type != "started") {
      throw Error(journal.path(), "unknown journal record type '" + type + "'");
    }
  }
  return state;
}

// Asks every question not yet answered, in plan order, again until the answer
// fits; each answer is journalled at once. False if the participant stopped.
bool AskQuestionnaire(const StudyPlan& plan, AnswerSource& answers, Journal& journal,
                      std::map<std::string, json>* answered, std::ostream& out) {
  const size_t n = plan.questionnaire.size();
  if (answered->size() == n) return true;
  out << "Questionnaire: " << n - answered->size() << " questions about your experience "
      << "(q stops for now).\n";
  for (size_t i = 0; i < n; ++i) {
    const Question& q = plan.questionnaire[i];
    if (answered->count(q.id)) continue;
    for (;;) {
      const std::optional<std::string> typed = answers.NextLine(
          "Question " + std::to_string(i + 1) + "/" + std::to_string(n) + ": " + QuestionPrompt(q));
      if (!typed) return false;
      std::string why;
      const std::optional<json> value = ParseAnswer(q, *typed, &why);
      if (!value) {
        out << why << "\n";
        continue;
      }
      const json rec = {{"type", "answer"},
                        {"id", q.id},
                        {"answer", *value},
                        {"answered_utc", UtcNow()},
                        {"scripted", answers.scripted()}};
      journal.Append(rec);
      answered->emplace(q.id, rec);
      break;
    }
  }
  return true;
}

// Every file the session plays, before the first clip: a track that is a
// FIFO or a device would hang or fail the player in the middle of a sitting.
void CheckSessionFiles(const StudyPlan& plan, bool verify_hashes) {
  for (const auto& c : plan.clips) {
    CheckRegularFile(c.video);
    for (const auto& [cond, t] : c.tracks) CheckRegularFile(t.path);
  }
  if (!verify_hashes) return;
  for (const auto& c : plan.clips) {
    if (HashFile(c.video) != c.video_hash)
      throw Error(c.video, "video changed since the plan was made (hash differs)");
    for (const auto& [cond, t] : c.tracks)
      if (HashFile(t.path) != t.hash)
        throw Error(t.path, "haptic track changed since the plan was made (hash differs)");
  }
}

// Plays one clip with one condition's track through the player command.
class ClipPlayer {
 public:
  ClipPlayer(const StudyPlan& plan, const RunOptions& options)
      : plan_(plan),
        device_(options.device),
        words_(SplitCommand(options.player_cmd.empty() ? kDefaultPlayerTemplate
                                                       : options.player_cmd)),
        exe_(SelfExecutable()) {}

  void Play(const std::string& clip_name, const std::string& condition) const {
    const StudyClip& clip = plan_.Clip(clip_name);
    const std::string& track = clip.tracks.at(condition).path;
    const auto argv = SubstituteCommand(words_, {{"exe", exe_},
                                                 {"video", clip.video},
                                                 {"track", track},
                                                 {"device", device_},
                                                 {"clip", clip_name},
                                                 {"condition", condition}});
    const int rc = RunChild(argv);
    if (rc != 0)
      throw Error(track, "player exited with status " + std::to_string(rc) + " (" + argv[0] + ")");
  }

 private:
  const StudyPlan& plan_;
  std::string device_;
  std::vector<std::string> words_;
  std::string exe_;
};

void RunTraining(const ParticipantPlan& who, const ClipPlayer& player, Journal& journal,
                 std::ostream& out) {
  out << "Training: " << who.training.size() << " clips with one kind of haptic feedback.\n";
  for (size_t i = 0; i < who.training.size(); ++i) {
    out << "  training " << i + 1 << "/" << who.training.size() << ": " << who.training[i].clip
        << "\n"
        << std::flush;
    player.Play(who.training[i].clip, who.training[i].condition);
  }
  journal.Append({{"type", "training_done"}, {"utc", UtcNow()}});
}

// Plays each pair until the participant answers (0 = replay); nullopt when
// they stopped. Sets *rt_s to the time from the end of the pair to the answer.
std::optional<int> AskTrial(const Trial& t, int total, const ClipPlayer& player,
                            AnswerSource& answers, std::ostream& out, double* rt_s) {
  std::optional<int> choice;
  for (;;) {
    if (answers.Exhausted()) return std::nullopt;
    out << "Trial " << t.index + 1 << "/" << total << " (" << t.clip << "): sequence 1...\n"
        << std::flush;
    player.Play(t.clip, t.first.front());
    out << "  sequence 2...\n" << std::flush;
    player.Play(t.clip, t.second.front());
    const auto asked = std::chrono::steady_clock::now();
    choice = answers.Next();
    *rt_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
    if (!choice || *choice != 0) return choice;
  }
}

// Every trial not yet answered; false if the participant stopped.
bool RunTrials(const ParticipantPlan& who, const ClipPlayer& player, AnswerSource& answers,
               Journal& journal, std::map<int, json>* answered, RunSummary* summary,
               std::ostream& out) {
  for (const Trial& t : who.trials) {
    if (answered->count(t.index)) continue;
    double rt_s = 0;
    const std::optional<int> choice = AskTrial(t, summary->total, player, answers, out, &rt_s);
    if (!choice) {
      out << "Stopped after " << answered->size() << " of " << summary->total
          << " trials; answers are saved in " << journal.path()
          << ". Run the same command again to resume.\n";
      return false;
    }
    const json rec = {
        {"type", "trial"},         {"index", t.index},         {"clip", t.clip},
        {"first", t.first},        {"second", t.second},       {"choice", *choice},
        {"response_time_s", rt_s}, {"answered_utc", UtcNow()}, {"scripted", answers.scripted()}};
    journal.Append(rec);
    answered->emplace(t.index, rec);
    ++summary->answered_now;
  }
  return true;
}

// The results of a complete session, assembled from the journal (the single
// source of truth).
ParticipantResults AssembleResults(const StudyPlan& plan, const ParticipantPlan& who,
                                   const RunOptions& options, const Journal& journal,
                                   const JournalState& state) {
  ParticipantResults res;
  res.plan_id = plan.plan_id;
  res.participant = who.id;
  res.device = options.device;
  res.conditions = plan.conditions;
  for (const auto& c : plan.clips) res.clips.push_back({c.name, c.groups});
  res.training_condition = who.training_condition;
  for (const auto& r : journal.records()) {
    if (r.value("type", "") == "started" && res.started_utc.empty())
      res.started_utc = r.value("utc", "");
  }
  res.completed_utc = UtcNow();
  for (const auto& [idx, r] : state.trials) {
    TrialResult tr;
    tr.index = idx;
    tr.clip = r["clip"].get<std::string>();
    tr.first = r["first"].get<std::vector<std::string>>();
    tr.second = r["second"].get<std::vector<std::string>>();
    tr.choice = r["choice"].get<int>();
    tr.response_time_s = r["response_time_s"].get<double>();
    tr.answered_utc = r["answered_utc"].get<std::string>();
    res.trials.push_back(std::move(tr));
  }
  for (const Question& q : plan.questionnaire) {
    const json& r = state.question_answers.at(q.id);
    res.questionnaire.push_back({q, r["answer"], r["answered_utc"].get<std::string>()});
  }
  return res;
}

std::string DefaultResultsPath(const RunOptions& options, const ParticipantPlan& who) {
  if (!options.results_path.empty()) return options.results_path;
  const fs::path dir = fs::path(options.plan_path).parent_path();
  return (dir / (who.id + ".results.json")).string();
}

void CreateParentFolder(const std::string& file) {
  const fs::path dir = fs::path(file).parent_path();
  if (dir.empty()) return;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir.string(), "cannot create the results folder: " + ec.message());
}

void PrintResuming(const ParticipantPlan& who, const RunSummary& summary,
                   const JournalState& state, const Journal& journal, std::ostream& out) {
  out << "Resuming " << who.id << ": " << summary.answered_before << " of " << summary.total
      << " trials already answered"
      << (state.question_answers.empty()
              ? ""
              : ", " + std::to_string(state.question_answers.size()) + " of " +
                    std::to_string(summary.questions) + " questions")
      << " (" << journal.path() << ")\n";
}

}  // namespace

RunSummary RunSession(const RunOptions& options, std::istream& in, std::ostream& out) {
  options.Check();
  const StudyPlan plan = ReadPlanFile(options.plan_path);
  const ParticipantPlan& who = plan.Participant(options.participant);

  RunSummary summary;
  summary.total = static_cast<int>(who.trials.size());
  summary.results_path = DefaultResultsPath(options, who);
  summary.journal_path = JournalPathFor(summary.results_path);
  CheckSessionFiles(plan, options.verify_hashes);

  AnswerSource answers(options.responses_path, in, out);
  CreateParentFolder(summary.results_path);
  Journal journal(summary.journal_path, plan.plan_id, who.id);
  JournalState state = ReadJournalState(journal, plan, who);
  summary.questions = static_cast<int>(plan.questionnaire.size());
  summary.answered_before = static_cast<int>(state.trials.size());
  if (summary.answered_before > 0 || state.training_done)
    PrintResuming(who, summary, state, journal, out);
  journal.Append({{"type", "started"}, {"utc", UtcNow()}, {"device", options.device}});

  const ClipPlayer player(plan, options);
  if (!state.training_done) RunTraining(who, player, journal, out);
  if (!RunTrials(who, player, answers, journal, &state.trials, &summary, out)) return summary;

  const bool questionnaire_done =
      AskQuestionnaire(plan, answers, journal, &state.question_answers, out);
  summary.questions_answered = static_cast<int>(state.question_answers.size());
  if (!questionnaire_done) {
    out << "Stopped at the questionnaire after " << summary.questions_answered << " of "
        << summary.questions << " questions; answers are saved in " << journal.path()
        << ". Run the same command again to resume.\n";
    return summary;
  }
  const ParticipantResults res = AssembleResults(plan, who, options, journal, state);
  ResultsFromJson(ResultsToJson(res), summary.results_path);  // self-check before writing
  WriteResultsFile(res, summary.results_path);
  summary.complete = true;
  out << "Done: " << summary.total << " trials answered; results in " << summary.results_path
      << "\n";
  return summary;
}

}  // namespace hapcine::study
