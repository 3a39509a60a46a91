// `hapcine make`: one film in, camera path and haptic track out, in one
// command. It takes every option of `estimate` and `haptics` (their own
// option tables, read through ScopedAppProbe: no copy to drift) and runs the
// film through batch's per-film runner (batch/make.h), which reuses the
// camera path while the film and the estimate settings are unchanged.

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "batch/job_progress.h"
#include "batch/make.h"
#include "cli/cmd_haptics_platform.h"
#include "cli/command.h"
#include "core/error.h"
#include "core/output_files.h"
#include "estimate/shot_quality.h"
#include "haptics/haptic_edits.h"

namespace hapcine::cli {
namespace {
namespace fs = std::filesystem;

// Options of estimate/haptics that make sets itself or that write files of
// their own outside the film's layout.
const std::map<std::string, std::string>& RefusedOptions() {
  static const std::map<std::string, std::string> refused = {
      {"--output", "make names the outputs (use -o DIR for their folder)"},
      {"--report", "run `hapcine estimate --report` for a report"},
      {"--report-detail", "run `hapcine estimate --report --report-detail` for a report"},
      {"--effects-out", "run `hapcine haptics --effects-out` on the camera path"},
      {"--print-seat", "run `hapcine haptics --print-seat`"},
  };
  return refused;
}

struct SplitArguments {
  std::vector<std::string> make;  // make's own, for its CLI::App
  std::vector<std::string> estimate, haptics;
};

// Deals each word of argv to make, estimate or haptics by the option tables
// (an option both take goes to both); make's own options win.
SplitArguments Split(int argc, char** argv, const CLI::App& make_app) {
  const OptionTable est = OptionsOf(RunEstimate, "estimate");
  const OptionTable hap = OptionsOf(RunHaptics, "haptics");
  SplitArguments split;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const std::string name = word.substr(0, word.find('='));
    const bool inline_value = name.size() < word.size();
    const CLI::Option* own = name.rfind("-", 0) == 0 && name.size() > 1
                                 ? make_app.get_option_no_throw(name)
                                 : nullptr;
    const bool foreign = !own && (est.count(name) || hap.count(name));
    if (!foreign) {
      split.make.push_back(word);
      if (own && own->get_items_expected_max() > 0 && !inline_value && i + 1 < argc)
        split.make.push_back(argv[++i]);
      continue;
    }
    const auto refused = RefusedOptions().find(name);
    if (refused != RefusedOptions().end() || name == "-o")
      throw UsageError(name + " is not an option of make: " +
                       (refused != RefusedOptions().end() ? refused->second : "use -o DIR"));
    const bool takes_value = est.count(name) ? est.at(name) : hap.at(name);
    std::vector<std::string> words = {word};
    if (takes_value && !inline_value && i + 1 < argc) words.push_back(argv[++i]);
    if (est.count(name)) split.estimate.insert(split.estimate.end(), words.begin(), words.end());
    if (hap.count(name)) split.haptics.insert(split.haptics.end(), words.begin(), words.end());
  }
  return split;
}

// Parses `args` with `command`'s own options, so that a bad value is a usage
// error now rather than a failed step after minutes of estimation.
void CheckArguments(int (*run)(int, char**), const std::string& command,
                    std::vector<std::string> args) {
  ScopedAppProbe probe([&](CLI::App& app, int argc, char** argv) {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      throw UsageError(std::string(command) + " option: " + e.what());
    }
    return 0;
  });
  std::vector<std::string> words = {"hapcine " + command, "in.mp4", "-o", "out.csv"};
  if (command == "haptics") words[1] = "in.camera.csv";
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  run(static_cast<int>(words.size()), argv.data());
}

// The shot's quality; a zoom-ambiguous one also says in how many frames (as
// `hapcine estimate` warns and the batch summary counts), and one read as a
// still camera before a moving subject says so.
std::string ShotLine(const ShotQuality& q) {
  std::ostringstream s;
  if (q.doubtful) {
    s << DoubtfulShotLine(q);
  } else {
    s << std::fixed << std::setprecision(2) << "shot " << q.shot << " (frames " << q.first_frame << "-"
      << q.last_frame << "): ok, " << q.lost << " of " << q.frames << " frames lost, median confidence "
      << q.median_confidence;
    if (q.inlier_ratio) s << ", inlier ratio " << *q.inlier_ratio;
    if (q.rms_px) s << ", rms " << *q.rms_px << " px";
  }
  if (q.zoom_ambiguous.value_or(0) > 0)
    s << ", zoom ambiguous in " << *q.zoom_ambiguous << " of " << q.frames << " frames";
  if (q.still_border) s << ", read as a still camera (its border stays still: a subject's motion)";
  return s.str();
}

void PrintSummary(const batch::MakeOptions& options, const batch::MakeResult& r, std::ostream& out) {
  const batch::FilmLayout& l = r.layout;
  const fs::path dir(l.output_dir);
  const std::vector<ShotQuality> shots = ReadShotQualityOfFile((dir / l.camera).string());
  const ShotQualityCounts counts = CountShotQuality(shots);
  out << "make: " << options.film << ": " << counts.shots << " shot(s)";
  if (counts.doubtful > 0) out << ", " << counts.doubtful << " doubtful";
  if (counts.zoom_ambiguous > 0) out << ", " << counts.zoom_ambiguous << " zoom ambiguous";
  out << ", model " << options.model << ", " << FormatDuration(r.outcome.seconds) << "\n";
  for (const batch::StepRecord& s : r.outcome.steps) {
    out << "  " << std::left << std::setw(20) << s.name
        << (s.reused ? "reused (film and settings unchanged)" : "ran " + FormatDuration(s.seconds))
        << "\n";
  }
  if (r.outcome.status == batch::FilmStatus::kSkipped)
    out << "  every output up to date (film and settings unchanged)\n";
  for (const ShotQuality& q : shots) out << "  " << ShotLine(q) << "\n";
  const std::vector<std::pair<std::string, std::string>> files = {
      {"camera path", l.camera},     {"haptic track", l.models.front().haptic},
      {"hjif", l.models.front().hjif}, {"preview", l.preview},
      {"camera plot", l.camera_plot}, {"haptic plot", l.haptic_plot}};
  for (const auto& [what, name] : files) {
    if (!name.empty()) out << "  " << std::left << std::setw(13) << what << (dir / name).string() << "\n";
  }
}

// Runs the film on a worker thread while this one redraws the progress.
batch::MakeResult RunWithProgress(const batch::MakeOptions& options, ProgressMode mode) {
  const batch::FilmPlan film = batch::MakeFilmPlan(options.film);
  const batch::FilmLayout layout = batch::MakeLayout(options, film);
  if (!layout.edits.empty()) {
    ReadHapticEditsFile(layout.edits);  // a bad file fails now, not after the estimate
    std::cerr << "make: edits from " << layout.edits << " (--no-edits to ignore)\n";
  }
  return batch::RunMakeWithProgress(options, layout, std::cerr, mode, "make");
}

}  // namespace

int RunMake(int argc, char** argv) {
  CLI::App app{
      "Film in, haptics out: writes FILM's camera path (<stem>.camera.csv) and haptic track\n"
      "(<stem>.haptic.csv, the name `play` looks for) beside the film or in -o DIR, and on\n"
      "request a .hjif, a preview video and plots. Every option of `hapcine estimate` (e.g.\n"
      "--draft) and of `hapcine haptics` (e.g. --washout-tau, --seat) is taken too. The camera\n"
      "path is reused while the film's content and the estimate options are unchanged, so\n"
      "another model or haptics option costs seconds. State and step logs:\n"
      "<output folder>/.hapcine/<stem>-<8 hex>/. Details: docs/make.md.",
      "hapcine make"};
  batch::MakeOptions opt;
  std::string progress = "auto";
  bool quiet = false;
  app.add_option("FILM", opt.film, "the video (anything FFmpeg reads)")->required();
  app.add_option("-o,--out", opt.out_dir, "output folder (created); default: the film's folder");
  app.add_option("--model", opt.model, "haptic model: cinematic, semantic, random or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"cinematic", "semantic", "random", "none"}));
  app.add_flag("--hjif", opt.hjif, "also write <stem>.hjif (MPEG-I Haptics interchange file)");
  app.add_flag("--preview", opt.preview,
               "also render <stem>.preview.mp4: the film with the actuators drawn in an inset");
  app.add_flag("--plot", opt.plot, "also draw <stem>.camera.png and <stem>.haptic.png");
  app.add_flag("--force", opt.force, "redo every step, even those whose results are up to date");
  bool no_edits = false;
  app.add_flag("--no-edits", no_edits,
               "ignore <stem>.edits.json (a designer's per-shot gains, models, washout and\n"
               "keyframes, docs/formats.md), which is otherwise used when it is beside the\n"
               "outputs or beside the film");
  app.add_option("--progress", progress, "auto (bar on a terminal, lines otherwise), bar, lines or quiet")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bar", "lines", "quiet"}));
  app.add_flag("-q,--quiet", quiet, "no progress output (the closing summary is still printed)");
  app.add_option("--hapcine-exe", opt.step_exe, "program run for the steps (default: this executable)");
  app.footer("Estimate options: hapcine estimate --help.  Haptics options: hapcine haptics --help.");

  SplitArguments split;
  try {
    split = Split(argc, argv, app);
  } catch (const UsageError& e) {
    std::cerr << "hapcine make: " << e.what() << "\n";
    return kExitUsage;
  }
  std::vector<std::string> own = {argv[0]};
  own.insert(own.end(), split.make.begin(), split.make.end());
  std::vector<char*> own_argv;
  for (std::string& w : own) own_argv.push_back(w.data());
  own_argv.push_back(nullptr);
  return RunApp(app, static_cast<int>(own.size()), own_argv.data(), [&]() -> int {
    CheckArguments(RunEstimate, "estimate", split.estimate);
    CheckArguments(RunHaptics, "haptics", split.haptics);
    opt.use_edits = !no_edits && !ArgumentsChoosePlatform(split.haptics);
    if (!no_edits && !opt.use_edits) std::cerr << "make: a motion platform takes no edits file\n";
    opt.estimate_args = split.estimate;
    opt.haptics_args = split.haptics;
    batch::CheckMakeOptions(opt);  // before the progress bar: a usage error is one line
    if (!opt.out_dir.empty()) CheckOutputPaths({{opt.film, "FILM"}}, {{opt.out_dir, "-o", true}});
    const ProgressMode mode = quiet || progress == "quiet" ? ProgressMode::kQuiet
                              : progress == "bar"          ? ProgressMode::kBar
                              : progress == "lines"        ? ProgressMode::kLines
                                                           : ProgressModeFor(false);
    const batch::MakeResult r = RunWithProgress(opt, mode);
    PrintSummary(opt, r, std::cerr);
    return kExitOk;
  });
}

}  // namespace hapcine::cli
