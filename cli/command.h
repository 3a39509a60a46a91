#pragma once
// The `hapcine` program is a thin dispatcher: each subcommand lives in its own
// cmd_<name>.cc, maps its flags onto the options struct of a library function,
// and calls it. Exit codes: 0 success, 1 failure (one line: file and reason),
// 2 usage error.

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <string>

namespace hapcine::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// Parses argv with `app` and runs `body`, mapping exceptions to exit codes:
// CLI11 parse errors and UsageError -> 2, hapcine::Error and other
// std::exceptions -> 1 with "hapcine <cmd>: <message>" on stderr.
int RunApp(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

// Lets one command use another's options without a copy of them (`hapcine
// make` takes every option of estimate and haptics): while a probe is set on
// this thread, RunApp hands the command's CLI::App and arguments to it
// instead of parsing and running, and returns what the probe returns.
using AppProbe = std::function<int(CLI::App& app, int argc, char** argv)>;
class ScopedAppProbe {
 public:
  explicit ScopedAppProbe(AppProbe probe);
  ~ScopedAppProbe();
  ScopedAppProbe(const ScopedAppProbe&) = delete;
  ScopedAppProbe& operator=(const ScopedAppProbe&) = delete;

 private:
  AppProbe probe_;
  AppProbe* previous_;
};

// Option name ("--tracks", "-q") -> takes a value, of the command `run`
// (read through a ScopedAppProbe: nothing is parsed or run).
using OptionTable = std::map<std::string, bool>;
OptionTable OptionsOf(int (*run)(int, char**), const std::string& command);

// One function per subcommand; argv[0] is "hapcine <name>".
int RunSynth(int argc, char** argv);
int RunEstimate(int argc, char** argv);
int RunHaptics(int argc, char** argv);
int RunPlay(int argc, char** argv);
int RunPreview(int argc, char** argv);
int RunEval(int argc, char** argv);
int RunPlot(int argc, char** argv);
int RunBatch(int argc, char** argv);
int RunStudy(int argc, char** argv);
int RunConvert(int argc, char** argv);
int RunMake(int argc, char** argv);
int RunStudio(int argc, char** argv);

}  // namespace hapcine::cli
