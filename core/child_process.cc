#include "core/child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <thread>

#include "core/stop_signal.h"

extern char** environ;

namespace hapcine {
namespace {

constexpr auto kPoll = std::chrono::milliseconds(20);

// Fills *result from a waitpid status.
void Record(int status, ChildResult* result) {
  if (WIFEXITED(status)) result->exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result->term_signal = WTERMSIG(status);
}

// Polls until the child has exited or `deadline` passed; true if it exited.
bool WaitUntil(pid_t pid, std::chrono::steady_clock::time_point deadline, ChildResult* result) {
  for (;;) {
    int status = 0;
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      Record(status, result);
      return true;
    }
    if (r < 0 && errno != EINTR) return true;  // not our child any more: nothing to wait for
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace

ChildResult RunChild(const std::vector<std::string>& argv, const std::string& log_path,
                     double grace_s) {
  ChildResult result;
  if (argv.empty()) {
    result.start_errno = EINVAL;
    return result;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // The child starts with default SIGINT/SIGTERM actions (exec resets caught
  // signals) and no blocked signals, whatever this process has installed.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);

  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    result.start_errno = rc;
    return result;
  }
  result.started = true;

  const auto forever = std::chrono::steady_clock::time_point::max();
  for (;;) {
    const auto next = std::chrono::steady_clock::now() + kPoll;
    if (WaitUntil(pid, next, &result)) break;
    if (!StopRequested()) continue;
    result.stopped = true;
    kill(pid, SIGTERM);
    const auto grace = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(static_cast<long>(grace_s * 1000));
    if (!WaitUntil(pid, grace, &result)) {
      kill(pid, SIGKILL);
      WaitUntil(pid, forever, &result);
    }
    break;
  }
  // A child that a terminal's Ctrl-C killed together with us counts as stopped.
  if (StopRequested()) result.stopped = true;
  return result;
}

}  // namespace hapcine
