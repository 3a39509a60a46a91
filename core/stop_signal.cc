#include "core/stop_signal.h"

#include <atomic>
#include <csignal>

#include "core/output_files.h"

namespace hapcine {

namespace {
// 0: running; -1: stop requested by the program; > 0: the signal number.
std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "signal flag must be lock-free");
struct sigaction g_old_int, g_old_term;
bool g_installed = false;

extern "C" void OnStopSignal(int sig) {
  if (g_stop.load(std::memory_order_relaxed) != 0) {
    // Second signal: the loop did not stop; fall back to the default action,
    // without leaving the temporaries of unfinished outputs behind.
    RemoveLiveTempsForSignal();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_stop.store(sig, std::memory_order_relaxed);
}
}  // namespace

void InstallStopSignals() {
  if (g_installed) return;
  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
  g_installed = true;
}

void RestoreStopSignals() {
  if (!g_installed) return;
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
  g_installed = false;
}

bool StopRequested() { return g_stop.load(std::memory_order_relaxed) != 0; }
int StopSignal() {
  const int s = g_stop.load(std::memory_order_relaxed);
  return s > 0 ? s : 0;
}
void RequestStop() {
  int expected = 0;
  g_stop.compare_exchange_strong(expected, -1, std::memory_order_relaxed);
}
void ClearStopRequest() { g_stop.store(0, std::memory_order_relaxed); }

}  // namespace hapcine
