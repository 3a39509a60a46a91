// `hapcine batch`: a whole library through estimate + haptics, locally with N
// workers or as a Slurm job array; resumable. The work is in batch/.

#include <algorithm>
#include <iostream>
#include <sstream>

#include "batch/batch.h"
#include "batch/library.h"
#include "batch/progress.h"
#include "batch/slurm.h"
#include "cli/cmd_haptics_platform.h"
#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/error.h"
#include "core/output_files.h"

namespace hapcine::cli {

namespace {

// "cinematic,semantic" -> {"cinematic", "semantic"} (empty names dropped).
std::vector<std::string> SplitModels(const std::string& models) {
  std::vector<std::string> names;
  std::stringstream ms(models);
  for (std::string m; std::getline(ms, m, ',');) {
    if (!m.empty()) names.push_back(m);
  }
  return names;
}

void PrintTotals(const batch::BatchSummary& s) {
  std::cerr << "batch: " << s.films.size() << " films: " << s.Count(batch::FilmStatus::kDone)
            << " done, " << s.Count(batch::FilmStatus::kSkipped) << " skipped, "
            << s.Count(batch::FilmStatus::kFailed) << " failed, "
            << s.Count(batch::FilmStatus::kDuplicate) << " duplicate in "
            << FormatDuration(s.wall_seconds) << "\n";
  const auto edited = std::count_if(s.films.begin(), s.films.end(),
                                    [](const batch::FilmOutcome& f) { return !f.edits.empty(); });
  if (edited > 0) {
    std::cerr << "batch: " << edited << " film(s) with an edits file (<stem>.edits.json, listed in "
              << "summary.txt; --no-edits to ignore)\n";
  }
}

// Everything the command line sets besides BatchOptions and SlurmOptions.
struct BatchArgs {
  std::string positional;  // LIBRARY, or OUT_DIR with --status
  std::string models = "cinematic,semantic";
  std::string estimate_args, haptics_args, shard, sbatch_args, progress = "auto";
  bool use_slurm = false, no_wait = false, status = false, no_edits = false;
};

// The library, the outputs, the steps' arguments and the progress.
void AddLibraryOptions(CLI::App& app, BatchArgs* a, batch::BatchOptions* opt) {
  app.add_option("LIBRARY", a->positional,
                 "folder (searched recursively for video files by extension) or manifest\n"
                 "(text: one path per line, # comments; or .csv with a 'path' column).\n"
                 "With --status: the OUT_DIR to report on");
  app.add_option("-o,--out", opt->out_dir, "output folder (created; shared by re-runs and shards)");
  app.add_option("-j,--jobs", opt->jobs,
                 "films processed in parallel (per Slurm task with --slurm); 0 = number of "
                 "CPUs")
      ->default_val(0)
      ->check(FiniteRange(0, 1024));
  app.add_option("--models", a->models, "comma-separated haptic models, one haptics step each")
      ->default_val(a->models);
  app.add_option("--estimate-args", a->estimate_args,
                 "extra arguments for every `hapcine estimate` step (shell-style quoting)");
  app.add_option("--haptics-args", a->haptics_args,
                 "extra arguments for every `hapcine haptics` step (shell-style quoting)");
  app.add_option("--hapcine-exe", opt->step_exe,
                 "program run for the steps (default: this hapcine executable)");
  app.add_flag("--force", opt->force, "redo every film even if up to date");
  app.add_flag("--no-edits", a->no_edits,
               "ignore the films' <stem>.edits.json files (otherwise used when beside a film\n"
               "or in its output folder; docs/formats.md \"Edits file\")");
  app.add_flag("--status", a->status,
               "print progress of OUT_DIR from its state files (done/failed/duplicate/\n"
               "running/pending) and exit");
  app.add_option("--progress", a->progress,
                 "auto (bar on a terminal, lines otherwise), bar, lines or quiet")
      ->default_val(a->progress)
      ->check(CLI::IsMember({"auto", "bar", "lines", "quiet"}));
}

// The Slurm job array, and the shard each of its tasks runs.
void AddSlurmOptions(CLI::App& app, BatchArgs* a, batch::SlurmOptions* slurm) {
  app.add_flag("--slurm", a->use_slurm, "submit as a Slurm job array instead of running here");
  app.add_option("--shards", slurm->shards,
                 "with --slurm: array tasks (capped at the number of films)")
      ->default_val(slurm->shards)
      ->check(FiniteRange(1, 100000));
  app.add_flag("--no-wait", a->no_wait, "with --slurm: return after submitting (then use --status)");
  app.add_option("--wait-timeout", slurm->wait_timeout_s,
                 "with --slurm: stop waiting after this many seconds; 0 = never")
      ->default_val(0)
      ->check(FiniteRange(0, 1e7));
  app.add_option("--sbatch-args", a->sbatch_args,
                 "with --slurm: extra sbatch arguments, e.g. \"--partition=x --time=1:00:00\"");
  app.add_option("--shard", a->shard, "i/K: process only shard i of K (what each Slurm task runs)");
}

// `--status`: OUT_DIR's progress from its state files.
int PrintStatus(const BatchArgs& a, const batch::BatchOptions& opt) {
  const std::string out = opt.out_dir.empty() ? a.positional : opt.out_dir;
  if (out.empty()) throw UsageError("--status needs OUT_DIR");
  std::cout << batch::ReadBatchStatus(out).ToText();
  return kExitOk;
}

// "i/K" -> shard i of K.
void ParseShard(const std::string& shard, batch::BatchOptions* opt) {
  char slash = 0;
  std::istringstream ss(shard);
  if (!(ss >> opt->shard_index >> slash >> opt->shard_count) || slash != '/' || !ss.eof()) {
    throw UsageError("--shard must look like i/K, e.g. 0/4");
  }
}

batch::BatchOptions::Progress ProgressFromName(const std::string& progress) {
  return progress == "bar"     ? batch::BatchOptions::Progress::kBar
         : progress == "lines" ? batch::BatchOptions::Progress::kLines
         : progress == "quiet" ? batch::BatchOptions::Progress::kQuiet
                               : batch::BatchOptions::Progress::kAuto;
}

// The command line's choices into `opt`, with the output folder's name checked.
void CompleteOptions(const BatchArgs& a, batch::BatchOptions* opt) {
  opt->library = a.positional;
  opt->use_edits = !a.no_edits;
  // Outputs are committed as each film finishes; only the names are checked.
  CheckOutputPaths({{opt->library, "LIBRARY"}}, {{opt->out_dir, "-o", /*folder=*/true}});
  opt->models = SplitModels(a.models);
  opt->estimate_args = batch::SplitArgs(a.estimate_args);
  opt->haptics_args = batch::SplitArgs(a.haptics_args);
  if (ArgumentsChoosePlatform(opt->haptics_args)) {
    opt->use_edits = false;  // only the HapSeat models take an edits file
    if (!a.no_edits) std::cerr << "batch: a motion platform takes no edits files\n";
  }
  if (!a.shard.empty()) ParseShard(a.shard, opt);
  opt->progress = ProgressFromName(a.progress);
}

}  // namespace

int RunBatch(int argc, char** argv) {
  CLI::App app{
      "Process a video library: for every film `hapcine estimate` (camera path), then\n"
      "`hapcine haptics` for each model, each step a child process so one bad film never\n"
      "stops the batch. Re-running the same command resumes: films whose content and\n"
      "settings are unchanged are skipped, changed ones are redone, failures retried.\n"
      "Outputs: OUT_DIR/<stem>-<8 hex>/<stem>.camera.csv, <stem>.<model>.haptic.csv,\n"
      "<stem>.<model>.hjif, done.json; OUT_DIR/summary.json and summary.txt.\n"
      "Details: docs/batch.md.",
      "hapcine batch"};
  BatchArgs a;
  batch::BatchOptions opt;
  batch::SlurmOptions slurm;
  AddLibraryOptions(app, &a, &opt);
  AddSlurmOptions(app, &a, &slurm);

  return RunApp(app, argc, argv, [&]() -> int {
    if (a.status) return PrintStatus(a, opt);
    CompleteOptions(a, &opt);
    if (a.use_slurm) {
      if (!a.shard.empty()) throw UsageError("--slurm and --shard exclude each other");
      slurm.wait = !a.no_wait;
      slurm.sbatch_args = batch::SplitArgs(a.sbatch_args);
      return batch::SubmitSlurmBatch(opt, slurm);
    }
    const batch::BatchSummary s = batch::RunLocalBatch(opt);
    PrintTotals(s);
    return s.ExitCode();
  });
}

}  // namespace hapcine::cli
