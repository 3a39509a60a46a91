#include "cli/command.h"

#include <iostream>

#include "core/error.h"
#include "core/error_message.h"
#include "core/input_file.h"

namespace hapcine::cli {
namespace {
thread_local AppProbe* current_probe = nullptr;
}  // namespace

ScopedAppProbe::ScopedAppProbe(AppProbe probe) : probe_(std::move(probe)), previous_(current_probe) {
  current_probe = &probe_;
}

ScopedAppProbe::~ScopedAppProbe() { current_probe = previous_; }

OptionTable OptionsOf(int (*run)(int, char**), const std::string& command) {
  OptionTable table;
  ScopedAppProbe probe([&](CLI::App& app, int, char**) {
    for (const CLI::Option* o : app.get_options()) {
      const bool takes_value = o->get_items_expected_max() > 0;
      for (const std::string& n : o->get_lnames()) table["--" + n] = takes_value;
      for (const std::string& n : o->get_snames()) table["-" + n] = takes_value;
    }
    return 0;
  });
  std::string prog = "hapcine " + command;
  char* argv[] = {prog.data(), nullptr};
  run(1, argv);
  return table;
}

int RunApp(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  if (current_probe) return (*current_probe)(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // prints help, returns 0
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": " << EscapeControlChars(e.what()) << "\n"
              << "Run '" << app.get_name() << " --help' for usage.\n";
    return kExitUsage;
  }
  ForgetInputOfEscapedException();
  try {
    return body();
  } catch (const UsageError& e) {
    std::cerr << app.get_name() << ": " << EscapeControlChars(e.what()) << "\n";
    return kExitUsage;
  } catch (...) {
    // Anything else, hapcine::Error or not, is one line naming the file.
    std::cerr << app.get_name() << ": " << EscapedExceptionMessage(std::current_exception())
              << "\n";
    return kExitFailure;
  }
}

}  // namespace hapcine::cli
