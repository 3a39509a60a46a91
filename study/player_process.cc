#include "study/player_process.h"

#include <fcntl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>

#include "core/error.h"

namespace hapcine::study {

std::vector<std::string> SplitCommand(const std::string& command) {
  std::vector<std::string> words;
  std::string cur;
  bool in_word = false;
  char quote = 0;
  for (char ch : command) {
    if (quote) {
      if (ch == quote) {
        quote = 0;
      } else {
        cur += ch;
      }
    } else if (ch == '\'' || ch == '"') {
      quote = ch;
      in_word = true;
    } else if (ch == ' ' || ch == '\t' || ch == '\n') {
      if (in_word) words.push_back(cur);
      cur.clear();
      in_word = false;
    } else {
      cur += ch;
      in_word = true;
    }
  }
  if (quote) throw UsageError("unclosed quote in player command: " + command);
  if (in_word) words.push_back(cur);
  return words;
}

std::vector<std::string> SubstituteCommand(const std::vector<std::string>& words,
                                           const std::map<std::string, std::string>& vars) {
  std::vector<std::string> out;
  for (std::string w : words) {
    for (const auto& [key, value] : vars) {
      const std::string pat = "{" + key + "}";
      for (size_t pos = w.find(pat); pos != std::string::npos;
           pos = w.find(pat, pos + value.size()))
        w.replace(pos, pat.size(), value);
    }
    out.push_back(w);
  }
  return out;
}

std::string SelfExecutable() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "hapcine";
  return std::string(buf, static_cast<size_t>(n));
}

int RunChild(const std::vector<std::string>& argv) {
  if (argv.empty()) throw UsageError("empty player command");
  std::vector<char*> cargv;
  for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  // A pipe closed on exec tells the parent whether exec itself failed.
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw Error(argv[0], std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw Error(argv[0], std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    close(fds[0]);
    execvp(cargv[0], cargv.data());
    const int err = errno;
    ssize_t ignored = write(fds[1], &err, sizeof err);
    (void)ignored;
    _exit(127);
  }
  close(fds[1]);
  int exec_errno = 0;
  ssize_t got;
  do {
    got = read(fds[0], &exec_errno, sizeof exec_errno);
  } while (got < 0 && errno == EINTR);
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error(argv[0], std::string("waitpid: ") + std::strerror(errno));
  }
  if (got == static_cast<ssize_t>(sizeof exec_errno))
    throw Error(argv[0], std::string("cannot start player: ") + std::strerror(exec_errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace hapcine::study
