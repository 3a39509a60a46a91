#pragma once
// Errors that reach the user. Every failure the CLI reports is one line:
// "<file>: <reason>" (or "<file>:<line>: <reason>" for text formats), so that
// a batch log says at once which input was bad and why.

#include <stdexcept>
#include <string>

namespace hapcine {

class Error : public std::runtime_error {
 public:
  // `where` names the file (and line, if any); `reason` says what is wrong.
  Error(const std::string& where, const std::string& reason)
      : std::runtime_error(where.empty() ? reason : where + ": " + reason),
        where_(where),
        reason_(reason) {}
  const std::string& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string where_;
  std::string reason_;
};

// Thrown for bad command-line usage; the CLI maps it to exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace hapcine
