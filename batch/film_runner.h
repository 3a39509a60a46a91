#pragma once
// Processes one film of a batch: estimate, then haptics for each model, each
// step a child process writing into <film>/.tmp/, its outputs renamed into
// <film>/ on success, done.json written last. Holds the film's lock while it
// works, so two batches (or Slurm tasks) never process the same film at once.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/batch_options.h"
#include "batch/plan.h"

namespace hapcine::batch {

enum class FilmStatus {
  kDone,       // processed now
  kSkipped,    // already done for the same content and settings
  kFailed,     // a step failed (reason recorded in failed.json)
  kDuplicate,  // same bytes as another film; processed there
  kBusy,       // another process holds its lock
};
const char* FilmStatusName(FilmStatus s);

struct StepRecord {
  std::string name;      // "estimate", "haptics-cinematic", ...
  double seconds = 0.0;  // wall time of the step (0 if reused)
  bool reused = false;   // an up-to-date result of an earlier run was kept
};

struct FilmOutcome {
  std::string id;
  std::string path;
  FilmStatus status = FilmStatus::kFailed;
  std::string reason;        // failure: "<step>: exit 1: <stderr line>"
  std::string duplicate_of;  // duplicate: the film id holding the outputs
  double seconds = 0.0;      // wall time spent on the film in this run
  std::vector<StepRecord> steps;
  // From the camera path's `# shot_quality.<shot>=` header lines
  // (docs/formats.md): shots, those flagged doubtful, lost frames; -1 when
  // the film has no camera path or its header has no summary.
  int shots = -1, doubtful_shots = 0, lost_frames = 0;
};

// Fills the three counts above from a camera path's header lines.
void ReadShotQualityCounts(const std::string& camera_csv, FilmOutcome* outcome);

nlohmann::json OutcomeToJson(const FilmOutcome& o);
FilmOutcome OutcomeFromJson(const nlohmann::json& j);

// The step commands of a film (exposed for tests and docs).
std::vector<std::string> EstimateCommand(const BatchOptions& options, const std::string& exe,
                                         const std::string& input, const std::string& camera_csv);
std::vector<std::string> HapticsCommand(const BatchOptions& options, const std::string& exe,
                                        const std::string& camera_csv, const std::string& model,
                                        const std::string& haptic_csv, const std::string& hjif);

// Processes (or skips) one film. Never throws for a failing film; the
// failure is in the outcome and in <film>/failed.json.
FilmOutcome ProcessFilm(const BatchOptions& options, const std::string& step_exe,
                        const std::string& settings_hash, const FilmPlan& film);

// True if <film>/done.json records this content and these settings and every
// output it lists is present with its recorded size.
bool FilmIsDone(const std::string& film_dir, const FilmPlan& film,
                const std::string& settings_hash);

}  // namespace hapcine::batch
