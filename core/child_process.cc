#include "core/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

#include "core/error.h"
#include "core/input_file.h"
#include "core/stop_signal.h"

namespace hapcine {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::milliseconds(20);

// Waits for the child until `deadline` (polling), or without a deadline
// (blocking); true once it has been reaped, with its status in *status.
bool WaitUntil(pid_t pid, const Clock::time_point* deadline, int* status) {
  for (;;) {
    const pid_t r = ::waitpid(pid, status, deadline ? WNOHANG : 0);
    if (r == pid) return true;
    if (r < 0 && errno != EINTR) return true;  // not our child any more: nothing to wait for
    if (deadline == nullptr) continue;         // EINTR
    if (Clock::now() >= *deadline) return false;
    std::this_thread::sleep_for(kPoll);
  }
}

// The child's side of fork: only async-signal-safe calls until exec. On
// exec failure, errno goes through `exec_error_fd` and the log says why.
[[noreturn]] void ExecInChild(char* const* cargv, pid_t parent, int null_fd, int log_fd,
                              int exec_error_fd) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);  // parent died before prctl
  // Default SIGINT/SIGTERM (exec resets caught signals; this unblocks them).
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
  ::dup2(log_fd, STDOUT_FILENO);
  ::dup2(log_fd, STDERR_FILENO);
  ::execvp(cargv[0], cargv);
  const int err = errno;
  if (exec_error_fd >= 0) (void)!::write(exec_error_fd, &err, sizeof(err));
  const char* msg = "cannot execute step program: ";
  (void)!::write(STDERR_FILENO, msg, std::strlen(msg));
  (void)!::write(STDERR_FILENO, cargv[0], std::strlen(cargv[0]));
  (void)!::write(STDERR_FILENO, "\n", 1);
  ::_exit(127);
}

// The parent's side of the exec pipe: the child's errno if exec failed
// (a successful exec closes the pipe with nothing written).
void ReadExecError(int exec_pipe[2], ChildResult* result) {
  if (exec_pipe[1] < 0) return;
  ::close(exec_pipe[1]);
  int err = 0;
  ssize_t n;
  while ((n = ::read(exec_pipe[0], &err, sizeof(err))) < 0 && errno == EINTR) {
  }
  ::close(exec_pipe[0]);
  if (n == static_cast<ssize_t>(sizeof(err))) {
    result->started = false;
    result->start_errno = err;
  }
}

// Waits for the child; on a stop request, SIGTERM, then SIGKILL after the
// grace period.
int WaitOrStop(pid_t pid, const ChildOptions& options, ChildResult* result) {
  int status = 0;
  if (!options.stop_on_request) {
    WaitUntil(pid, nullptr, &status);
    return status;
  }
  for (;;) {
    const Clock::time_point next = Clock::now() + kPoll;
    if (WaitUntil(pid, &next, &status)) break;
    if (!StopRequested()) continue;
    result->stopped = true;
    ::kill(pid, SIGTERM);
    const Clock::time_point grace =
        Clock::now() + std::chrono::milliseconds(static_cast<long>(options.grace_s * 1000));
    if (!WaitUntil(pid, &grace, &status)) {
      ::kill(pid, SIGKILL);
      WaitUntil(pid, nullptr, &status);
    }
    break;
  }
  // A child that a terminal's Ctrl-C ended together with us counts as stopped.
  if (StopRequested()) result->stopped = true;
  return status;
}

}  // namespace

ChildResult RunChild(const std::vector<std::string>& argv, const std::string& log_path,
                     const ChildOptions& options) {
  if (argv.empty()) throw Error("", "RunChild: empty command");
  // Everything the child needs is prepared before fork: between fork and exec
  // a multi-threaded parent's child may only make async-signal-safe calls.
  std::vector<char*> cargv;
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  const int mode = options.append_log ? O_APPEND : O_TRUNC;
  const int log_fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | mode | O_CLOEXEC, 0644);
  if (log_fd < 0) throw Error(log_path, std::string("cannot create log: ") + std::strerror(errno));
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  // exec failure is reported through this pipe (closed by a successful exec).
  int exec_pipe[2] = {-1, -1};
  if (::pipe2(exec_pipe, O_CLOEXEC) != 0) exec_pipe[0] = exec_pipe[1] = -1;
  const pid_t parent = ::getpid();
  const auto t0 = Clock::now();

  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    for (int fd : {log_fd, null_fd, exec_pipe[0], exec_pipe[1]})
      if (fd >= 0) ::close(fd);
    throw Error(argv[0], std::string("cannot fork: ") + std::strerror(err));
  }
  if (pid == 0) ExecInChild(cargv.data(), parent, null_fd, log_fd, exec_pipe[1]);
  ::close(log_fd);
  if (null_fd >= 0) ::close(null_fd);

  ChildResult result;
  result.started = true;
  ReadExecError(exec_pipe, &result);
  const int status = WaitOrStop(pid, options, &result);
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.term_signal = WTERMSIG(status);
  return result;
}

std::string LastNonEmptyLine(const std::string& path, size_t max_bytes) {
  if (!IsRegularFile(path)) return "";
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

}  // namespace hapcine
