#pragma once
// Diagnostics of a run: what the algorithms decided and how long their
// stages took, handed to a sink the caller injects (in the manner of Ceres'
// IterationCallback or OpenCV videostab's ILog). The algorithms never print
// and read no environment: the CLI writes what a sink collected
// (`hapcine estimate --report`, docs/formats.md "Estimate report"), tests read
// it. No sink (a null pointer) listens to nothing and costs nothing.

#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

namespace hapcine {

class Diagnostics {
 public:
  virtual ~Diagnostics() = default;
  // Whether records of `kind` are wanted: the costly ones (a line per track
  // or per frame) are computed only then.
  virtual bool Wants(const std::string& kind) const = 0;
  // One record of `kind` ("window", "cut_cues", ...): a JSON object. Any
  // thread may call it.
  virtual void Record(const std::string& kind, nlohmann::json fields) = 0;
};

// Null-safe helpers for the algorithms.
inline bool Wants(const Diagnostics* d, const std::string& kind) { return d && d->Wants(kind); }
inline void Record(Diagnostics* d, const std::string& kind, nlohmann::json fields) {
  if (d && d->Wants(kind)) d->Record(kind, std::move(fields));
}

// CPU seconds the calling thread has used.
double ThreadCpuSeconds();

// Wall seconds since construction; Lap(): since the last Lap (or construction).
class StageClock {
 public:
  StageClock() : start_(Clock::now()), lap_(start_) {}
  double Seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double Lap() {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - lap_).count();
    lap_ = now;
    return s;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_, lap_;
};

// A run's stages ("tracking done", ...): each a "stage" record with the wall
// seconds since the first and the calling thread's CPU seconds.
class StageLog {
 public:
  explicit StageLog(Diagnostics* d) : diagnostics_(d) {}
  void Stage(const std::string& name);

 private:
  Diagnostics* diagnostics_;
  StageClock clock_;
};

// Collects records into one JSON document: {"<kind>s": [record, ...], ...}
// in arrival order per kind (a kind ending in "s" is its own plural). `kinds`: those wanted (empty: every kind).
class JsonDiagnostics : public Diagnostics {
 public:
  explicit JsonDiagnostics(std::set<std::string> kinds = {}) : kinds_(std::move(kinds)) {}
  bool Wants(const std::string& kind) const override { return kinds_.empty() || kinds_.count(kind) > 0; }
  void Record(const std::string& kind, nlohmann::json fields) override;
  // A copy of what was collected so far, with `header`'s fields first.
  nlohmann::json Document(const nlohmann::json& header = nlohmann::json::object()) const;

 private:
  std::set<std::string> kinds_;
  mutable std::mutex mutex_;
  nlohmann::json records_ = nlohmann::json::object();
};

}  // namespace hapcine
