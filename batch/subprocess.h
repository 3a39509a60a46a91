#pragma once
// Runs one pipeline step as a child process, so that a crash, a hang killed
// by the user or a corrupt film takes down that step only, never the batch.
// The process handling (process group, PR_SET_PDEATHSIG, stdin /dev/null,
// stdout + stderr to a log) is core/child_process.h's; this adds the batch's
// failure record.

#include <string>
#include <vector>

#include "core/child_process.h"  // LastNonEmptyLine

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

// Runs argv[0] (searched in PATH when it has no '/') with argv, logging to
// log_path (created or truncated). Never throws for a failing child (one that
// cannot be executed exits 127, the reason in its log); throws hapcine::Error
// only for an empty argv, a log that cannot be created, or a failed fork.
ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& log_path);

}  // namespace hapcine::batch
