#pragma once
// Runs one pipeline step as a child process, so that a crash, a hang killed
// by the user or a corrupt film takes down that step only, never the batch.
//
// The child inherits the batch's process group (a Ctrl-C or a kill of the
// group stops the steps too) and gets PR_SET_PDEATHSIG=SIGKILL, so a step
// never outlives a batch killed with SIGKILL alone. stdin is /dev/null;
// stdout and stderr both go to a log file.

#include <string>
#include <vector>

namespace hapcine::batch {

struct ProcessResult {
  int exit_code = -1;     // exit status, or -1 if killed by a signal
  int signal = 0;         // terminating signal, 0 if it exited
  double seconds = 0.0;   // wall time
  std::string last_line;  // last non-empty line of the log (max 400 bytes)
  bool ok() const { return exit_code == 0 && signal == 0; }
  // One line for a failure record: "exit 1: <last line>" or
  // "killed by signal 11 (Segmentation fault): <last line>".
  std::string Reason() const;
};

// Runs argv[0] (a path, not searched in PATH) with argv, logging to log_path
// (created or truncated). Never throws for a failing child; throws
// hapcine::Error only if the log cannot be created or fork fails.
ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& log_path);

// Last non-empty line of a text file ("" if none or unreadable), trimmed and
// cut to max_bytes.
std::string LastNonEmptyLine(const std::string& path, size_t max_bytes = 400);

}  // namespace hapcine::batch
