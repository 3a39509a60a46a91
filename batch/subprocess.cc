#include "batch/subprocess.h"

#include <cstring>

namespace hapcine::batch {

std::string ProcessResult::Reason() const {
  std::string head;
  if (signal != 0) {
    head = "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  } else {
    head = "exit " + std::to_string(exit_code);
  }
  return last_line.empty() ? head : head + ": " + last_line;
}

ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& log_path) {
  const ChildResult child = RunChild(argv, log_path);
  ProcessResult r;
  r.exit_code = child.exit_code;
  r.signal = child.term_signal;
  r.seconds = child.seconds;
  r.last_line = LastNonEmptyLine(log_path);
  return r;
}

}  // namespace hapcine::batch
