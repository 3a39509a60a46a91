#include "core/diagnostics.h"

#include <time.h>

namespace hapcine {

double ThreadCpuSeconds() {
  timespec cpu{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
  return cpu.tv_sec + 1e-9 * cpu.tv_nsec;
}

void StageLog::Stage(const std::string& name) {
  if (!Wants(diagnostics_, "stage")) return;
  diagnostics_->Record("stage", {{"name", name}, {"wall_s", clock_.Seconds()}, {"thread_cpu_s", ThreadCpuSeconds()}});
}

void JsonDiagnostics::Record(const std::string& kind, nlohmann::json fields) {
  if (!Wants(kind)) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const bool plural = !kind.empty() && kind.back() == 's';
  records_[plural ? kind : kind + "s"].push_back(std::move(fields));
}

nlohmann::json JsonDiagnostics::Document(const nlohmann::json& header) const {
  nlohmann::json doc = header;
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [key, value] : records_.items()) doc[key] = value;
  return doc;
}

}  // namespace hapcine
