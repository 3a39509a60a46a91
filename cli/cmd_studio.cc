// `hapcine studio`: review and edit a film's haptics in the browser. Runs
// each film through `make`'s per-film runner (the camera path is estimated
// when missing or stale, reused otherwise), then serves the studio
// (studio/studio_server.h) until Ctrl-C.

#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "batch/job_progress.h"
#include "batch/library.h"
#include "batch/make.h"
#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/child_process.h"
#include "core/error.h"
#include "core/stop_signal.h"
#include "haptics/haptic_models.h"
#include "haptics/seat_geometry.h"
#include "platform/platform_config.h"
#include "studio/http_security.h"
#include "studio/studio_server.h"

namespace hapcine::cli {
namespace {
namespace fs = std::filesystem;

// Options of estimate that would write files outside the film's layout.
const std::map<std::string, std::string>& RefusedEstimateOptions() {
  static const std::map<std::string, std::string> refused = {
      {"-o", "the studio names the outputs (<stem>.camera.csv beside the film)"},
      {"--output", "the studio names the outputs (<stem>.camera.csv beside the film)"},
      {"--report", "run `hapcine estimate --report` for a report"},
      {"--report-detail", "run `hapcine estimate --report --report-detail` for a report"},
  };
  return refused;
}

// Deals argv to the studio (its own options and the films) or to estimate.
void SplitArguments(int argc, char** argv, const CLI::App& app, std::vector<std::string>* own,
                    std::vector<std::string>* estimate) {
  const OptionTable est = OptionsOf(RunEstimate, "estimate");
  const OptionTable hap = OptionsOf(RunHaptics, "haptics");
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const std::string name = word.substr(0, word.find('='));
    const bool option = name.size() > 1 && name[0] == '-';
    const CLI::Option* mine = option ? app.get_option_no_throw(name) : nullptr;
    std::vector<std::string>* to = own;
    if (option && !mine && !est.count(name) && hap.count(name))
      throw UsageError(name + " is a haptics option: set it per shot on the studio's page (or use "
                              "hapcine make / haptics)");
    if (option && !mine && est.count(name)) {
      const auto refused = RefusedEstimateOptions().find(name);
      if (refused != RefusedEstimateOptions().end())
        throw UsageError(name + " is not an option of studio: " + refused->second);
      to = estimate;
    }
    to->push_back(word);
    const bool takes_value = mine ? mine->get_items_expected_max() > 0 : option && est.count(name) && est.at(name);
    if (takes_value && name.size() == word.size() && i + 1 < argc) to->push_back(argv[++i]);
  }
}

// The films of the arguments: files as given, folders searched for videos;
// a film named twice is served once (one session per edits file).
std::vector<std::string> ExpandFilms(const std::vector<std::string>& inputs) {
  std::vector<std::string> films;
  std::set<std::string> seen;
  auto add = [&](const std::string& film) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(fs::absolute(film), ec);
    if (seen.insert(ec ? film : key.string()).second) films.push_back(film);
  };
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec) && !batch::IsImageSequenceInput(input)) {
      const std::vector<std::string> found = batch::ListLibrary(input);
      if (found.empty()) throw Error(input, "no video files in this folder");
      for (const std::string& film : found) add(film);
    } else {
      add(input);
    }
  }
  return films;
}

// make's runner on a worker thread while this one redraws the progress.
batch::MakeResult MakeWithProgress(const batch::MakeOptions& options, ProgressMode mode) {
  const batch::FilmPlan film = batch::MakeFilmPlan(options.film);
  return batch::RunMakeWithProgress(options, batch::MakeLayout(options, film), std::cerr, mode,
                                    "studio: " + fs::path(options.film).filename().string());
}

struct StudioArgs {
  std::vector<std::string> inputs;
  std::string host = "127.0.0.1", model = "cinematic", seat, web_dir, camera, progress = "auto";
  int port = 8787;
  bool open = false, force = false, quiet = false;
  std::vector<std::string> estimate;
};

// Each film through make, then its session (camera path, rendered track).
std::vector<std::unique_ptr<studio::FilmSession>> LoadFilms(const StudioArgs& a) {
  HapticOptions haptics;
  haptics.model = HapticModelFromName(a.model);
  if (!a.seat.empty()) haptics.seat = LoadSeatGeometryFile(a.seat);
  const ProgressMode mode = a.quiet || a.progress == "quiet" ? ProgressMode::kQuiet
                            : a.progress == "bar"            ? ProgressMode::kBar
                            : a.progress == "lines"          ? ProgressMode::kLines
                                                             : ProgressModeFor(false);
  std::vector<std::unique_ptr<studio::FilmSession>> films;
  if (!a.camera.empty()) {  // a camera path of the user's: no make
    std::error_code ec;
    if (a.inputs.size() != 1 || fs::is_directory(a.inputs[0], ec))
      throw UsageError("--camera goes with exactly one film");
    if (!fs::is_regular_file(a.inputs[0], ec)) throw Error(a.inputs[0], "no such file");
    films.push_back(std::make_unique<studio::FilmSession>(
        "f0", fs::absolute(a.inputs[0]).lexically_normal().string(), a.camera, haptics));
    return films;
  }
  for (const std::string& film : ExpandFilms(a.inputs)) {
    batch::MakeOptions make;
    make.film = film;
    make.model = a.model;
    make.estimate_args = a.estimate;
    if (!a.seat.empty()) make.haptics_args = {"--seat", a.seat};
    make.force = a.force;
    const batch::MakeResult r = MakeWithProgress(make, mode);
    const std::string camera = (fs::path(r.layout.output_dir) / r.layout.camera).string();
    films.push_back(std::make_unique<studio::FilmSession>("f" + std::to_string(films.size()),
                                                          r.outcome.path, camera, haptics));
  }
  return films;
}

// Serves until SIGINT/SIGTERM.
void Serve(std::vector<std::unique_ptr<studio::FilmSession>> films, const StudioArgs& a) {
  studio::ServerOptions options;
  options.host = a.host;
  options.port = a.port;
  if (!studio::IsLoopbackHost(a.host)) options.token = studio::NewToken();
  if (!a.web_dir.empty()) options.web = studio::WebFiles::Directory(a.web_dir);
  const size_t count = films.size();
  studio::StudioServer server(std::move(films), std::move(options));
  ScopedStopSignals stop_signals;
  server.Start();
  std::cout << "hapcine studio: serving " << count << " film(s) at " << server.Url() << std::endl;
  if (!studio::IsLoopbackHost(a.host))
    std::cout << "hapcine studio: reachable from other machines: every request needs the token above"
              << std::endl;
  if (a.open) {
    std::thread([url = server.Url()] { RunChild({"xdg-open", url}, "/dev/null"); }).detach();
  }
  while (!StopRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  server.Stop();
  std::cerr << "hapcine studio: stopped\n";
}

}  // namespace

int RunStudio(int argc, char** argv) {
  CLI::App app{
      "Review and edit films' haptics in the browser. Each FILM (or every video of a FOLDER)\n"
      "goes through `hapcine make` first: its camera path is estimated when missing or stale\n"
      "(progress with ETA), reused otherwise. Then a local web server shows the film beside its\n"
      "camera curves and haptic track; per-shot model, gain, mute and washout and the semantic\n"
      "keyframes are edited there, saved as <stem>.edits.json beside the film (which `make`,\n"
      "`batch` and `haptics --edits` honour), and exported as <stem>.haptic.csv, <stem>.hjif or\n"
      "<stem>.preview.mp4. Serves on 127.0.0.1 only unless --host says otherwise; then every\n"
      "request needs the token in the printed URL. Ctrl-C stops it. Every option of `hapcine\n"
      "estimate` (e.g. --draft) is taken too. Details: docs/studio.md.",
      "hapcine studio"};
  StudioArgs a;
  app.add_option("FILM_OR_FOLDER", a.inputs, "films (anything FFmpeg reads) or folders of films")
      ->required();
  app.add_option("--port", a.port, "TCP port (0: any free port)")
      ->capture_default_str()
      ->check(FiniteRange(0, 65535));
  app.add_option("--host", a.host,
                 "address to listen on; anything but a loopback address (e.g. 0.0.0.0) exposes\n"
                 "the studio to the network and requires the printed token")
      ->capture_default_str();
  app.add_flag("--open", a.open, "open the page in the default browser (xdg-open)");
  app.add_option("--model", a.model, "haptic model of every shot not edited: cinematic, semantic, random or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"cinematic", "semantic", "random", "none"}));
  app.add_option("--seat", a.seat, "HapSeat geometry JSON (see hapcine haptics --print-seat)");
  app.add_option("--web-dir", a.web_dir,
                 "serve the front end from this folder instead of the copy built in\n"
                 "(front-end work: edit studio/web/ and reload the page)");
  app.add_option("--camera", a.camera,
                 "use this camera path for the (one) film instead of running make (e.g. one you\n"
                 "estimated with your own settings, or a ground truth)")
      ->check(CLI::ExistingFile);
  app.add_flag("--force", a.force, "redo every make step, even those whose results are up to date");
  app.add_option("--progress", a.progress, "auto (bar on a terminal, lines otherwise), bar, lines or quiet")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bar", "lines", "quiet"}));
  app.add_flag("-q,--quiet", a.quiet, "no progress output while estimating");
  app.footer("Estimate options: hapcine estimate --help.  HTTP API and security: docs/studio.md.");

  std::vector<std::string> own = {argv[0]};
  try {
    SplitArguments(argc, argv, app, &own, &a.estimate);
  } catch (const UsageError& e) {
    std::cerr << "hapcine studio: " << e.what() << "\n";
    return kExitUsage;
  }
  std::vector<char*> own_argv;
  for (std::string& w : own) own_argv.push_back(w.data());
  own_argv.push_back(nullptr);
  return RunApp(app, static_cast<int>(own.size()), own_argv.data(), [&]() -> int {
    if (!a.seat.empty() && IsPlatformFile(a.seat))
      throw UsageError("--seat: the studio shows the HapSeat only, not a motion platform");
    Serve(LoadFilms(a), a);
    return kExitOk;
  });
}

}  // namespace hapcine::cli
