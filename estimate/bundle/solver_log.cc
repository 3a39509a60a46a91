#include "estimate/bundle/solver_log.h"

#include <glog/logging.h>

#include <cstdlib>

namespace hapcine {

void QuietSolverLog() {
  if (std::getenv("GLOG_minloglevel") != nullptr) return;  // the user asked for a level
  FLAGS_minloglevel = google::GLOG_ERROR;
}

}  // namespace hapcine
