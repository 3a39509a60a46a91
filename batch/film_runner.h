#pragma once
// Processes one film: estimate, then haptics for each model (then, on
// request, a preview and plots), each step a child process writing into
// <state>/.tmp/, its outputs renamed into the output folder on success,
// done.json written last. Holds the film's lock while it works, so two
// processes never work on the same film at once. `hapcine batch` runs it for
// every film of a library (outputs and state in OUT_DIR/<id>/), `hapcine
// make` for one film (outputs beside the film or in -o DIR, state in
// <that folder>/.hapcine/<id>/): one implementation of step reuse,
// atomicity and failure records for both.

#include <nlohmann/json.hpp>
#include <optional>
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
  // Shots with frames whose zoom decision was ambiguous (zoom_ambiguous > 0).
  int zoom_ambiguous_shots = 0;
  std::string edits;  // the edits file its haptics used; empty: none
};

// Where one film's outputs and state go, and which outputs it has.
struct ModelOutputs {
  std::string model;   // "cinematic", ...
  std::string haptic;  // haptic track file name
  std::string hjif;    // .hjif file name; empty: none
};
struct FilmLayout {
  std::string output_dir;  // outputs are renamed into this folder
  std::string state_dir;   // done.json, failed.json, .steps/, logs/, .tmp/, .lock
  std::string camera;      // camera path file name
  std::vector<ModelOutputs> models;
  std::string preview;      // preview video of the first model's track; empty: none
  std::string camera_plot;  // plot PNG file names; empty: none
  std::string haptic_plot;
  // The film's edits file passed to its haptics steps (empty: none) and the
  // hash of its bytes, part of the keys of the steps that read the track.
  std::string edits;
  std::string edits_hash;
};

// Sets layout->edits to the first existing regular file of `candidates`
// (unless options.use_edits is false or the haptics arguments already name
// an --edits file) and layout->edits_hash to its content hash.
void FindEditsFile(const BatchOptions& options, const std::vector<std::string>& candidates,
                   FilmLayout* layout);
// batch's: everything in OUT_DIR/<id>/, "<stem>.<model>.haptic.csv" and
// "<stem>.<model>.hjif" for every model.
FilmLayout BatchFilmLayout(const BatchOptions& options, const FilmPlan& film);

// Told of each step as it starts (`hapcine make` draws its progress from the
// step's log). Called from the thread running the film.
class FilmObserver {
 public:
  virtual ~FilmObserver() = default;
  // `reused`: kept from an earlier run, nothing runs.
  virtual void StepStarted(const std::string& step, const std::string& log_path, bool reused) = 0;
};

// Sets the four counts above from a camera path's header lines
// (core/shot_quality_header.h reads them); leaves them when there are none.
void ReadShotQualityCounts(const std::string& camera_csv, FilmOutcome* outcome);

nlohmann::json OutcomeToJson(const FilmOutcome& o);
FilmOutcome OutcomeFromJson(const nlohmann::json& j);

// The step commands of a film (exposed for tests and docs).
std::vector<std::string> EstimateCommand(const BatchOptions& options, const std::string& exe,
                                         const std::string& input, const std::string& camera_csv);
std::vector<std::string> HapticsCommand(const BatchOptions& options, const std::string& exe,
                                        const std::string& camera_csv, const std::string& model,
                                        const std::string& haptic_csv, const std::string& hjif);
// `hjif` empty: no --hjif.

// Processes (or skips) one film laid out as `layout`. Never throws for a
// failing film; the failure is in the outcome and in <state>/failed.json.
FilmOutcome RunFilm(const BatchOptions& options, const std::string& step_exe,
                    const std::string& settings_hash, const FilmPlan& film,
                    const FilmLayout& layout, FilmObserver* observer = nullptr);
// RunFilm with BatchFilmLayout.
FilmOutcome ProcessFilm(const BatchOptions& options, const std::string& step_exe,
                        const std::string& settings_hash, const FilmPlan& film);

// True if <state_dir>/done.json records this content and these settings and
// every output it lists is present in output_dir (default: state_dir) with
// its recorded size, and, when edits_hash is given, it was made with those
// edits ("" = none).
bool FilmIsDone(const std::string& state_dir, const FilmPlan& film,
                const std::string& settings_hash, const std::string& output_dir = "",
                const std::optional<std::string>& edits_hash = std::nullopt);

}  // namespace hapcine::batch
