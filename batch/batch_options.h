#pragma once
// Options of a batch run (`hapcine batch`), and the settings fingerprint that
// decides what a re-run must redo.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace hapcine::batch {

// The version whose outputs a batch records; a new version redoes every film.
std::string HapcineVersion();

// Absolute path of the running executable (/proc/self/exe).
std::string SelfExecutable();

struct BatchOptions {
  // Folder (searched recursively for videos) or manifest; see library.h.
  std::string library;
  // Output folder: one sub-folder per film plus the state (see docs/batch.md).
  std::string out_dir;
  // Films processed in parallel; 0 = number of CPUs.
  int jobs = 0;
  // Haptic models run on every camera path, one `hapcine haptics` each.
  std::vector<std::string> models = {"cinematic", "semantic"};
  // Extra words appended to every `hapcine estimate` / `hapcine haptics` step.
  std::vector<std::string> estimate_args;
  std::vector<std::string> haptics_args;
  // Program run for the steps as `<step_exe> estimate ...` and
  // `<step_exe> haptics ...`; empty = this executable. Tests point it at a
  // stand-in script.
  std::string step_exe;
  // Redo every film even if its outputs are up to date.
  bool force = false;
  // Honour a film's edits file, "<stem>.edits.json" beside its outputs or
  // beside the film (docs/formats.md): its haptics steps get --edits, and
  // the file's content joins their step keys (not the settings hash: a
  // film without edits keeps its key). false: --no-edits.
  bool use_edits = true;
  // Outputs beyond the camera path and haptic tracks (`hapcine make`):
  // a .hjif per model (batch: always), a preview video, camera and haptic plots.
  bool hjif = true;
  bool preview = false;
  bool plot = false;
  // Process only the films of shard `shard_index` of `shard_count` (Slurm
  // array tasks); 0 of 1 = everything.
  int shard_index = 0;
  int shard_count = 1;
  // Progress display on stderr.
  enum class Progress { kAuto, kBar, kLines, kQuiet };
  Progress progress = Progress::kAuto;

  // Throws UsageError for an empty library/out_dir, jobs < 0, no or bad
  // model names, or a bad shard.
  void Check() const;
  int ResolvedJobs() const;
  std::string ResolvedStepExe() const;
  bool sharded() const { return shard_count > 1; }
};

// Settings that change outputs, as recorded in done.json, and their hashes.
// Each step has its own key so a change of haptic model does not redo the
// (slow) estimate step. A step argument naming an existing file (`--seat
// seat.json`, `--keyframes=k.csv`) counts with the file's content, so editing
// that file makes the outputs made with it stale.
nlohmann::json SettingsJson(const BatchOptions& options);
std::string SettingsHash(const BatchOptions& options);
std::string EstimateStepKey(const BatchOptions& options);
std::string HapticsStepKey(const BatchOptions& options, const std::string& model);

// {"<word>": "fnv1a64:<hex>"} for each argument word (or the value of a
// `--name=value` word) that names an existing regular file, relative paths
// taken from the current folder (where the steps run).
nlohmann::json ArgumentFileHashes(const std::vector<std::string>& args);

}  // namespace hapcine::batch
