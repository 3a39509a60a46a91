#pragma once
// Runs the `hapcine` program under test (HAPCINE_EXE, set by CMake) the way a
// user's shell would, for the end-to-end tests of this folder.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "testpaths/test_paths.h"

namespace hapcine_test {

struct RunResult {
  int exit_code = -1;  // -1 when killed by a signal
  std::string out;     // stdout
  std::string err;     // stderr
};

inline std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `hapcine ARGS` through the shell, stdin from /dev/null (a test never waits
// on a terminal); stderr goes through DIR/stderr.txt, stdout through a pipe.
inline RunResult RunHapcine(const std::string& args, const std::filesystem::path& dir) {
  const std::filesystem::path err_file = dir / "stderr.txt";
  const std::string cmd = std::string("'") + HAPCINE_EXE + "' " + args + " </dev/null 2>'" +
                          err_file.string() + "'";
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = Slurp(err_file);
  return r;
}

inline std::string Quote(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// Last non-empty line of a text (progress output may come before an error).
inline std::string LastLine(const std::string& text) {
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

}  // namespace hapcine_test
