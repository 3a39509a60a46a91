#pragma once
// Runs an external program (COLMAP) as a child that a stop request can end.
// std::system would leave the child running if only this process got SIGTERM
// (e.g. `kill PID`, a batch scheduler's timeout) and could not tell "not
// found" from "failed". Here the child is started with posix_spawnp, its
// stdout and stderr are appended to a log file, and the parent polls both
// the child and StopRequested() (core/stop_signal.h): on a stop request the
// child gets SIGTERM, then SIGKILL if it has not exited within grace_s.

#include <string>
#include <vector>

namespace hapcine {

struct ChildResult {
  bool started = false;    // false: the program could not be spawned (start_errno)
  int start_errno = 0;     // ENOENT: not found in PATH
  bool stopped = false;    // ended by us on a stop request
  int exit_code = -1;      // the child's exit status when it exited normally
  int term_signal = 0;     // the signal that killed it, else 0

  bool ok() const { return started && !stopped && term_signal == 0 && exit_code == 0; }
};

// argv[0] is searched in PATH. log_path is created if missing and appended to.
ChildResult RunChild(const std::vector<std::string>& argv, const std::string& log_path,
                     double grace_s = 5.0);

}  // namespace hapcine
