#pragma once
// Running one participant's session (paper, section 5.2): the training block
// (each clip once with the participant's training condition), then the
// pairwise trials in the plan's order — clip with stimulus 1, clip with
// stimulus 2, "which did you prefer, 1 or 2?" — then the plan's post-test
// questionnaire, if any (one typed line per answer, asked again until valid). Each answer goes to
// the journal at once (fsync), so the session can be stopped at any time (a break, Ctrl-C, a crash)
// and resumed by running the same command again. When every trial and
// question is answered the results file is written atomically.

#include <istream>
#include <ostream>
#include <string>

namespace hapcine::study {

struct RunOptions {
  std::string plan_path;       // PLAN.json from `hapcine study plan`
  std::string participant;     // "P07" or "7"
  std::string device = "sim";  // passed to the player: sim, none or falcon
  // Player command template (see player_process.h); empty = kDefaultPlayerTemplate.
  std::string player_cmd;
  // File of scripted answers, one per line ("1" or "2" for a trial, then one
  // line per questionnaire answer; '#' comments and blank lines ignored),
  // consumed from the first unanswered trial or question on. Empty = ask
  // on the input stream (stdin).
  std::string responses_path;
  // Results file; empty = "<plan dir>/<participant id>.results.json". The
  // journal sits beside it as "<...>.journal.jsonl".
  std::string results_path;
  bool verify_hashes = true;  // re-hash videos and tracks, refuse if changed since planning
  void Check() const;         // throws UsageError
};

struct RunSummary {
  int total = 0;               // trials in the plan for this participant
  int answered_before = 0;     // found in the journal at start
  int answered_now = 0;        // answered in this run
  int questions = 0;           // in the plan's questionnaire
  int questions_answered = 0;  // so far, this run and before (set once the trials are done)
  bool complete = false;       // all answered and the results file written
  std::string results_path;
  std::string journal_path;
};

// `in` is where typed answers come from when no responses file is given;
// prompts and progress go to `out`. Returns when the session is complete or
// stops early (end of input or responses, or the participant typed "q").
// Throws Error if the player fails (the journal keeps what was answered).
RunSummary RunSession(const RunOptions& options, std::istream& in, std::ostream& out);

// The journal path that goes with a results path.
std::string JournalPathFor(const std::string& results_path);

}  // namespace hapcine::study
