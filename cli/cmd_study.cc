// hapcine study: the paper's pairwise user study (section 5) as three steps,
//   plan     clips + conditions -> PLAN.json (pairs, orders, training, hashes)
//   run      one participant's session through `hapcine play`, resumable
//   analyze  results files -> scores, Shapiro-Wilk, Friedman, Wilcoxon + Holm,
//            text table, SVG bar charts
// Each is a thin mapping of flags onto the study library (study/*.h).

#include <iostream>
#include <sstream>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/error.h"
#include "core/output_files.h"
#include "study/analysis.h"
#include "study/plan.h"
#include "study/player_process.h"
#include "study/questionnaire.h"
#include "study/report.h"
#include "study/results.h"
#include "study/session.h"

namespace hapcine::cli {
namespace {

// --questionnaire: "paper" (the built-in questions), a JSON file, or "" (none).
std::vector<study::Question> LoadQuestionnaire(const std::string& option) {
  if (option == "paper") return study::PaperQuestionnaire();
  if (option.empty()) return {};
  return study::ReadQuestionnaireFile(option);
}

// "12 of 78 answered", or with the trials done, the questionnaire's progress too.
std::string Progress(const study::RunSummary& s) {
  const int trials = s.answered_before + s.answered_now;
  std::string text = std::to_string(trials) + " of " + std::to_string(s.total) + " answered";
  if (trials == s.total && s.questions > 0)
    text += ", questionnaire " + std::to_string(s.questions_answered) + " of " +
            std::to_string(s.questions);
  return text;
}

// One struct per subcommand: its options, how they are declared, and what it
// does once parsed.
struct PlanCommand {
  study::PlanOptions options;
  std::string output;
  std::string conditions_csv = "cinematic,semantic,none,random";
  std::string questionnaire;
  CLI::App* app = nullptr;

  void Add(CLI::App& parent) {
    app = parent.add_subcommand(
        "plan",
        "Make a study plan. Each CLIP is a video `dir/<stem>.<ext>` with sibling tracks "
        "`dir/<stem>.<condition>.haptic.csv`, or a directory holding one video and "
        "`<condition>.haptic.csv`. Conditions with identical tracks (within the tolerance) are "
        "tested once (the paper's Vertigo: cinematic == none).");
    app->add_option("clips", options.clips, "Video files or clip directories")->required();
    app->add_option("-o,--output", output, "Plan file to write (JSON)")->required();
    app->add_option("--participants", options.participants,
                    "Number of participants to draw orders for (ids P01, P02, ...)")
        ->capture_default_str()
        ->check(FiniteRange(1, 100000));
    app->add_option("--seed", options.seed,
                    "Random seed; recorded in the plan, same seed and inputs -> same plan")
        ->capture_default_str()
        ->check(FiniteRange(0, 4294967295));
    app->add_option("--conditions", conditions_csv,
                    "Comma-separated haptic conditions (track names)")
        ->capture_default_str();
    app->add_option("--identical-tolerance-m", options.identical_tolerance_m,
                    "Tracks whose samples all agree within this many metres are the same "
                    "stimulus")
        ->capture_default_str()
        ->check(FiniteRange(0, 1));
    app->add_option("--questionnaire", questionnaire,
                    "Post-test questionnaire asked after the last trial: `paper` (the questions "
                    "built from the paper's section 6) or a JSON file of questions (see "
                    "docs/study.md). Default: none");
  }

  int Run() {
    options.conditions.clear();
    std::stringstream ss(conditions_csv);
    for (std::string c; std::getline(ss, c, ',');) options.conditions.push_back(c);
    std::vector<NamedPath> clips;
    for (const std::string& c : options.clips) clips.push_back({c, "CLIP"});
    if (questionnaire != "paper") clips.push_back({questionnaire, "--questionnaire"});
    options.questionnaire = LoadQuestionnaire(questionnaire);
    OutputSet outputs(clips, {{output, "-o"}});
    const study::StudyPlan p = study::MakePlan(options, &std::cerr);
    study::WritePlanFile(p, output);
    outputs.CommitAll();
    std::cerr << "plan " << p.plan_id << ": " << p.clips.size() << " clips, "
              << study::TrialsPerParticipant(p.clips) << " trials per participant, "
              << p.participants.size() << " participants -> " << output << "\n";
    return kExitOk;
  }
};

struct RunCommand {
  study::RunOptions options;
  bool no_verify = false;
  CLI::App* app = nullptr;

  void Add(CLI::App& parent) {
    app = parent.add_subcommand(
        "run",
        "Run one participant's session: training (each clip once with one random condition), "
        "then each pair (stimulus 1 then 2) and the answer: one key press (1 or 2, r replays, q "
        "stops) on a terminal, one line per answer from a pipe, or --responses FILE; then the "
        "plan's questionnaire, if any, one typed line per answer. Every answer is journalled at "
        "once (fsync): stop at any time (q, Ctrl-C) and run the same command again to resume. "
        "Exit 0 when complete (results file written), 1 if stopped early or on failure.");
    app->add_option("plan", options.plan_path, "Plan file from `hapcine study plan`")->required();
    app->add_option("--participant", options.participant, "Participant id (P07) or number (7)")
        ->required();
    app->add_option("--device", options.device,
                    "Haptic device passed to the player: sim, none or falcon")
        ->capture_default_str();
    app->add_option("--player-cmd", options.player_cmd,
                    std::string("Player command template; {exe} {video} {track} {device} {clip} "
                                "{condition} are replaced, no shell. Default: \"") +
                        study::kDefaultPlayerTemplate + "\" ({exe} = this program)");
    app->add_option("--responses", options.responses_path,
                    "Scripted answers, one 1 or 2 per line from the first unanswered trial, then "
                    "one line per questionnaire answer (default: ask on stdin)");
    app->add_option("-o,--results", options.results_path,
                    "Results file (default <plan dir>/<id>.results.json; journal beside it as "
                    "<id>.journal.jsonl)");
    app->add_flag("--no-verify", no_verify,
                  "Skip re-hashing the videos and tracks against the plan (default: verify)");
  }

  int Run() {
    options.verify_hashes = !no_verify;
    // Answers are journalled as they come; only the names are checked.
    CheckOutputPaths({{options.plan_path, "PLAN"}, {options.responses_path, "--responses"}},
                     {{options.results_path, "-o"}});
    const study::RunSummary s = study::RunSession(options, std::cin, std::cout);
    if (!s.complete) {
      std::cerr << "hapcine study run: " << s.journal_path << ": session incomplete ("
                << Progress(s) << "); run again to resume\n";
      return kExitFailure;
    }
    return kExitOk;
  }
};

struct AnalyzeCommand {
  std::vector<std::string> result_files;
  std::string prefix;
  CLI::App* app = nullptr;

  void Add(CLI::App& parent) {
    app = parent.add_subcommand(
        "analyze",
        "Score and test the results of one plan: per-condition and per-sequence normalised "
        "scores, Shapiro-Wilk, Friedman (participants as blocks), pairwise Wilcoxon signed-rank "
        "with Holm-Bonferroni. Prints a table; with -o also writes PREFIX.txt, PREFIX.json, "
        "PREFIX.overall.svg (Fig. 6) and PREFIX.sequences.svg (Fig. 7).");
    app->add_option("results", result_files,
                    "Results files (*.results.json) of the same plan")
        ->required();
    app->add_option("-o,--output", prefix, "Report prefix (default: print only)");
  }

  int Run() {
    std::vector<NamedPath> inputs, outputs;
    for (const auto& f : result_files) inputs.push_back({f, "RESULTS"});
    if (!prefix.empty()) {
      for (const char* suffix : {".txt", ".json", ".overall.svg", ".sequences.svg"})
        outputs.push_back({prefix + suffix, "-o"});
    }
    OutputSet report_files(inputs, outputs);
    std::vector<study::ParticipantResults> results;
    for (const auto& f : result_files) results.push_back(study::ReadResultsFile(f));
    const study::StudyAnalysis a = study::AnalyzeStudy(results);
    std::cout << study::FormatReport(a);
    if (!prefix.empty()) {
      const std::vector<std::string> written = study::WriteReport(a, prefix);
      report_files.CommitAll();
      for (const auto& path : written) std::cerr << "wrote " << path << "\n";
    }
    return kExitOk;
  }
};

}  // namespace

int RunStudy(int argc, char** argv) {
  CLI::App app{
      "Plan, run and analyse the pairwise user study of the paper (section 5): every pair of "
      "haptic conditions of every clip, in both orders, in a random order per participant; the "
      "participant picks the preferred of each pair. See docs/study.md.",
      "hapcine study"};
  app.require_subcommand(1);
  PlanCommand plan;
  RunCommand run;
  AnalyzeCommand analyze;
  plan.Add(app);
  run.Add(app);
  analyze.Add(app);
  return RunApp(app, argc, argv, [&]() -> int {
    if (plan.app->parsed()) return plan.Run();
    if (run.app->parsed()) return run.Run();
    return analyze.Run();
  });
}

}  // namespace hapcine::cli
