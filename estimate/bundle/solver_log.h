#pragma once
// What Ceres says on its own. Ceres reports through glog, to stderr: a step
// its trust region recovers from ("Linear solver failure ... Cholesky") comes
// out as a WARNING line between the program's progress lines. Those are the
// solver's business, not the user's: the result's quality is in the summary
// and the camera path's confidence.

namespace hapcine {

// Only glog messages of severity ERROR and above reach stderr, unless the
// environment sets GLOG_minloglevel (glog's own switch: 0 shows everything).
// No log files are written either way. Call once, first thing in main().
void QuietSolverLog();

}  // namespace hapcine
