#pragma once
// A stop request from SIGINT/SIGTERM, polled by long-running work: the haptic
// loop (zero force, then exit) and the COLMAP backend (kill its child, remove
// its temporary folder). The handler only stores to a lock-free atomic, so it
// is async-signal-safe; the work decides where it is safe to stop.
//
// InstallStopSignals() replaces the SIGINT/SIGTERM handlers and
// RestoreStopSignals() puts the previous ones back. A second signal while a
// stop is already pending falls through to the default action (immediate
// exit, after unlinking the live output temporaries: core/output_files.h), in
// case the work that should poll the flag is stuck. On the first signal the
// work stops and unwinds, so each output's destructor removes its temporary;
// RestoreStopSignals() then brings back the program's cleanup handler.

namespace hapcine {

void InstallStopSignals();
void RestoreStopSignals();
bool StopRequested();
int StopSignal();    // the signal that requested the stop (SIGINT, SIGTERM), else 0
void RequestStop();  // the same flag, e.g. from a button or a test
void ClearStopRequest();

// Installs on construction and restores on destruction (every exit path).
class ScopedStopSignals {
 public:
  ScopedStopSignals() { InstallStopSignals(); }
  ~ScopedStopSignals() { RestoreStopSignals(); }
  ScopedStopSignals(const ScopedStopSignals&) = delete;
  ScopedStopSignals& operator=(const ScopedStopSignals&) = delete;
};

}  // namespace hapcine
