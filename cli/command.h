#pragma once
// The `hapcine` program is a thin dispatcher: each subcommand lives in its own
// cmd_<name>.cc, maps its flags onto the options struct of a library function,
// and calls it. Exit codes: 0 success, 1 failure (one line: file and reason),
// 2 usage error.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace hapcine::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// Parses argv with `app` and runs `body`, mapping exceptions to exit codes:
// CLI11 parse errors and UsageError -> 2, hapcine::Error and other
// std::exceptions -> 1 with "hapcine <cmd>: <message>" on stderr.
int RunApp(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

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

}  // namespace hapcine::cli
