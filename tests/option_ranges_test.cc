// Every numeric option of every command has a range that the command line
// checks (cli/option_checks.h): the options are read from each command's own
// --help, each is fed its extremes (0, -1, 1e300, NaN, +-inf and its two
// bounds), and the command must answer 0, 1 or 2, and 2 (usage) for a value
// outside the range or not finite. The commands run in this process (a few
// hundred runs cost milliseconds, not a program start each): a crash ends
// the test binary, which fails it. The inputs named are missing, so a value
// in range ends in a quick failure, not in work.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.h"

namespace fs = std::filesystem;

namespace {

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// Runs `hapcine WORDS...` through its command's entry point, as main() does,
// capturing what it prints.
Outcome RunCommand(const std::vector<std::string>& words) {
  static const std::map<std::string, int (*)(int, char**)> kEntry = {
      {"synth", hapcine::cli::RunSynth},     {"estimate", hapcine::cli::RunEstimate},
      {"haptics", hapcine::cli::RunHaptics}, {"play", hapcine::cli::RunPlay},
      {"preview", hapcine::cli::RunPreview}, {"eval", hapcine::cli::RunEval},
      {"plot", hapcine::cli::RunPlot},       {"batch", hapcine::cli::RunBatch},
      {"study", hapcine::cli::RunStudy},     {"convert", hapcine::cli::RunConvert},
      {"make", hapcine::cli::RunMake}};
  std::vector<std::string> args = words;
  args[0] = "hapcine " + words[0];
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Outcome o;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  o.exit_code = kEntry.at(words[0])(static_cast<int>(args.size()), argv.data());
  o.out = ::testing::internal::GetCapturedStdout();
  o.err = ::testing::internal::GetCapturedStderr();
  return o;
}

struct NumericOption {
  std::string name;  // --long-name
  bool has_range = false;
  double lo = 0, hi = 0;
};

// Options of a --help text whose type is a number (CLI11: INT, UINT, FLOAT),
// with the "in [lo, hi]" that FiniteRange adds to the type.
std::vector<NumericOption> NumericOptions(const std::string& help) {
  static const std::regex kLine(
      R"(^\s+(?:-\w,)?(--[\w-]+)\s+(?:INT|UINT|FLOAT)\b(?::in \[([^,\]]+), ([^\]]+)\])?)");
  std::vector<NumericOption> found;
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, kLine)) continue;
    NumericOption o{m[1].str()};
    if (m[2].matched) {
      o.has_range = true;
      o.lo = std::strtod(m[2].str().c_str(), nullptr);
      o.hi = std::strtod(m[3].str().c_str(), nullptr);
    }
    found.push_back(o);
  }
  return found;
}

// A command (or sub-command) and arguments with which it fails at once on a
// missing input, when the options parse.
struct Command {
  std::string words;
  std::string args;  // DIR stands for a scratch folder
};

const Command kCommands[] = {
    {"synth", "no_such_preset -o DIR/synth"},
    {"estimate", "DIR/missing.mp4 -o DIR/out.camera.csv"},
    {"haptics", "DIR/missing.camera.csv -o DIR/out.haptic.csv"},
    {"play", "DIR/missing.mp4 --track DIR/missing.haptic.csv --device none --no-video"},
    {"preview", "DIR/missing.mp4 --track DIR/missing.haptic.csv -o DIR/out.mp4"},
    {"eval", "--gt DIR/missing.camera.csv --est DIR/missing2.camera.csv"},
    {"plot camera", "DIR/missing.camera.csv -o DIR/plot"},
    {"plot haptic", "DIR/missing.haptic.csv -o DIR/plot"},
    {"batch", "DIR/missing_library -o DIR/batch"},
    {"study plan", "DIR/missing.mp4 -o DIR/plan.json"},
    {"study run", "DIR/missing.plan.json --participant 1 -o DIR/r.results.json"},
    {"study analyze", "DIR/missing.results.json"},
    {"convert", "--from-tum DIR/missing.txt -o DIR/out.camera.csv"},
    {"make", "DIR/missing.mp4"},
};

class OptionRangesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hapcine_ranges_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> Args(const Command& c) const {
    std::string args = c.args;
    for (size_t p; (p = args.find("DIR")) != std::string::npos;) args.replace(p, 3, dir_.string());
    std::vector<std::string> all = Words(c.words);
    for (const auto& w : Words(args)) all.push_back(w);
    return all;
  }

  std::string Help(const Command& c) {
    std::vector<std::string> args = Words(c.words);
    args.push_back("--help");
    const Outcome o = RunCommand(args);
    EXPECT_EQ(o.exit_code, 0) << c.words << " --help";
    return o.out;
  }

  // Feeds `opt` its extremes and checks every answer.
  void FeedExtremes(const Command& c, const NumericOption& opt) {
    std::vector<std::string> values = {"0", "-1", "1e300", "nan", "inf", "-inf"};
    char bound[64];
    for (const double b : {opt.lo, opt.hi}) {
      std::snprintf(bound, sizeof bound, "%.17g", b);
      values.push_back(bound);
    }
    for (const std::string& value : values) {
      std::vector<std::string> args = Args(c);
      args.push_back(opt.name);
      args.push_back(value);
      const Outcome o = RunCommand(args);
      const std::string what = c.words + " " + opt.name + " " + value;
      EXPECT_TRUE(o.exit_code >= 0 && o.exit_code <= 2) << what << ": exit " << o.exit_code;
      const double v = std::strtod(value.c_str(), nullptr);
      const bool in_range = std::isfinite(v) && v >= opt.lo && v <= opt.hi;
      if (!in_range) {
        EXPECT_EQ(o.exit_code, 2) << what << "\n" << o.err;
        EXPECT_NE(o.err.find(opt.name), std::string::npos) << what << "\n" << o.err;
      } else {
        EXPECT_EQ(o.err.find("is outside"), std::string::npos) << what << "\n" << o.err;
      }
    }
  }

  fs::path dir_;
};

TEST_F(OptionRangesTest, EveryNumericOptionHasARange) {
  size_t total = 0;
  for (const Command& c : kCommands) {
    for (const NumericOption& o : NumericOptions(Help(c))) {
      EXPECT_TRUE(o.has_range) << c.words << " " << o.name << ": no range in --help";
      EXPECT_LE(o.lo, o.hi) << c.words << " " << o.name;
      ++total;
    }
  }
  EXPECT_GE(total, 60u);  // the help format is still the one parsed here
}

TEST_F(OptionRangesTest, ExtremeValuesAreUsageErrorsNeverCrashes) {
  for (const Command& c : kCommands) {
    for (const NumericOption& o : NumericOptions(Help(c))) {
      if (o.has_range) FeedExtremes(c, o);
    }
  }
}

}  // namespace
