#pragma once
// Opening a file to read it. Readers take regular files only: a FIFO blocks
// the reader (and a whole batch) until someone writes to it, /dev/zero never
// ends, a directory reads as empty. Every reader opens its input here, so all
// of them refuse these with the same one line, Error(path, reason).
//
// InputScope names the input a command was reading when an exception that
// is not a hapcine::Error (std::bad_alloc, ...) escapes, so that the CLI can
// still print "hapcine <cmd>: <file>: out of memory".

#include <fstream>
#include <string>

namespace hapcine {

// Throws Error(path, reason) unless `path` names a regular file (symlinks
// followed): "no such file", "is a directory", "not a regular file".
void CheckRegularFile(const std::string& path);

// The same test without throwing.
bool IsRegularFile(const std::string& path) noexcept;

// While alive, notes `path` (which must outlive it) as the input being read;
// if an exception unwinds past it, the innermost such path is kept for
// InputOfEscapedException(). Costs no allocation while unwinding.
class InputScope {
 public:
  explicit InputScope(const std::string& path);
  ~InputScope();
  InputScope(const InputScope&) = delete;
  InputScope& operator=(const InputScope&) = delete;

 private:
  const std::string path_;  // a copy: callers pass temporaries (fs::path::string())
  int exceptions_at_entry_;
};

// The path noted by the innermost InputScope an exception left on this
// thread since the last ForgetInputOfEscapedException(); "" if none.
std::string InputOfEscapedException();
void ForgetInputOfEscapedException();

// A regular file opened for reading, under an InputScope. Throws Error as
// CheckRegularFile does, or "cannot open for reading (<reason>)".
class InputFile {
 public:
  explicit InputFile(const std::string& path, std::ios::openmode mode = std::ios::in);
  std::ifstream& stream() { return in_; }

 private:
  InputScope scope_;
  std::ifstream in_;
};

}  // namespace hapcine
