#pragma once
// Runs an external program as a child process: a pipeline step of a batch
// (a crash or a corrupt film takes down that step only) or a COLMAP step of
// `estimate --backend colmap`.
//
// - stdin is /dev/null; stdout and stderr both go to a log file.
// - The child inherits our process group (a Ctrl-C in the terminal reaches it
//   too) and gets PR_SET_PDEATHSIG=SIGKILL, so it never outlives a parent
//   killed with SIGKILL alone.
// - With stop_on_request, the parent polls StopRequested() (core/stop_signal.h)
//   while it waits: a SIGTERM sent to this process alone (`kill PID`, a
//   scheduler's timeout) then reaches the child as SIGTERM, and SIGKILL
//   follows if it has not exited within grace_s. std::system could do
//   neither, nor tell "not found" from "failed".

#include <string>
#include <vector>

namespace hapcine {

struct ChildOptions {
  bool append_log = false;       // append to the log; otherwise create or truncate it
  bool stop_on_request = false;  // end the child when StopRequested() becomes true
  double grace_s = 5.0;          // SIGTERM -> SIGKILL delay for a stop request
};

struct ChildResult {
  bool started = false;   // false: exec failed (start_errno; exit_code 127)
  int start_errno = 0;    // ENOENT: no such program
  bool stopped = false;   // a stop request ended the wait (stop_on_request)
  int exit_code = -1;     // exit status, or -1 if killed by a signal
  int term_signal = 0;    // the terminating signal, 0 if it exited
  double seconds = 0.0;   // wall time
  bool ok() const { return started && !stopped && exit_code == 0 && term_signal == 0; }
};

// Runs argv[0] (searched in PATH when it has no '/') with argv. Never throws
// for a failing child; throws hapcine::Error for an empty argv, a log that
// cannot be opened, or a failed fork.
ChildResult RunChild(const std::vector<std::string>& argv, const std::string& log_path,
                     const ChildOptions& options = {});

// Last non-empty line of a text file ("" if none or unreadable), trimmed and
// cut to max_bytes on a UTF-8 character boundary.
std::string LastNonEmptyLine(const std::string& path, size_t max_bytes = 400);

}  // namespace hapcine
