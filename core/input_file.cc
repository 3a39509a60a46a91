#include "core/input_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>

#include "core/error.h"

namespace hapcine {
namespace {

// Fixed storage: filled while an exception (maybe std::bad_alloc) unwinds.
constexpr size_t kMaxNotedPath = 4096;
thread_local char g_escaped_input[kMaxNotedPath] = {0};

}  // namespace

void CheckRegularFile(const std::string& path) {
  if (path.empty()) throw Error(path, "empty input path");
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw Error(path, "no such file");
    throw Error(path, std::string("cannot read the file (") + std::strerror(errno) + ")");
  }
  if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory");
  if (!S_ISREG(st.st_mode)) throw Error(path, "not a regular file");
}

bool IsRegularFile(const std::string& path) noexcept {
  struct stat st;
  return !path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// Entering or leaving a scope normally means any earlier exception was
// handled: its note is forgotten. While one unwinds, the innermost scope
// (destroyed first) writes the note and the outer ones keep it.
InputScope::InputScope(const std::string& path)
    : path_(path), exceptions_at_entry_(std::uncaught_exceptions()) {
  g_escaped_input[0] = '\0';
}

InputScope::~InputScope() {
  if (std::uncaught_exceptions() <= exceptions_at_entry_) {
    g_escaped_input[0] = '\0';
    return;
  }
  if (g_escaped_input[0] != '\0') return;  // an inner scope already named its file
  const size_t n = std::min(path_.size(), kMaxNotedPath - 1);
  std::memcpy(g_escaped_input, path_.data(), n);
  g_escaped_input[n] = '\0';
}

std::string InputOfEscapedException() { return g_escaped_input; }

void ForgetInputOfEscapedException() { g_escaped_input[0] = '\0'; }

InputFile::InputFile(const std::string& path, std::ios::openmode mode) : scope_(path) {
  CheckRegularFile(path);
  in_.open(path, mode);
  if (!in_) {
    throw Error(path, std::string("cannot open for reading (") + std::strerror(errno) + ")");
  }
}

}  // namespace hapcine
