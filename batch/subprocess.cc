#include "batch/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>

#include "core/error.h"

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

std::string LastNonEmptyLine(const std::string& path, size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  // Only the tail matters; logs of a verbose step can be long.
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > 64 * 1024 ? size - 64 * 1024 : 0;
  in.seekg(start);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string last;
  size_t pos = 0;
  while (pos <= tail.size()) {
    size_t nl = tail.find_first_of("\r\n", pos);
    if (nl == std::string::npos) nl = tail.size();
    std::string line = tail.substr(pos, nl - pos);
    const size_t b = line.find_first_not_of(" \t");
    if (b != std::string::npos) {
      const size_t e = line.find_last_not_of(" \t");
      last = line.substr(b, e - b + 1);
    }
    pos = nl + 1;
  }
  if (last.size() > max_bytes) {
    size_t cut = max_bytes;
    while (cut > 0 && (static_cast<unsigned char>(last[cut]) & 0xC0) == 0x80) --cut;
    last = last.substr(0, cut) + "...";
  }
  return last;
}

ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& log_path) {
  if (argv.empty()) throw Error("", "RunProcess: empty command");
  // Everything the child needs is prepared before fork: between fork and exec
  // a multi-threaded parent's child may only make async-signal-safe calls.
  std::vector<char*> cargv;
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  const int log_fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) throw Error(log_path, std::string("cannot create log: ") + std::strerror(errno));
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const pid_t parent = ::getpid();
  const auto t0 = std::chrono::steady_clock::now();

  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(log_fd);
    if (null_fd >= 0) ::close(null_fd);
    throw Error(argv[0], std::string("cannot fork: ") + std::strerror(err));
  }
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // parent died before prctl
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::execv(cargv[0], cargv.data());
    const char* msg = "cannot execute step program: ";
    (void)!::write(STDERR_FILENO, msg, std::strlen(msg));
    (void)!::write(STDERR_FILENO, cargv[0], std::strlen(cargv[0]));
    (void)!::write(STDERR_FILENO, "\n", 1);
    ::_exit(127);
  }
  ::close(log_fd);
  if (null_fd >= 0) ::close(null_fd);

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
  }
  ProcessResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  r.last_line = LastNonEmptyLine(log_path);
  return r;
}

}  // namespace hapcine::batch
