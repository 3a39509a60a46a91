#pragma once
// `hapcine make`: one film in, its camera path and haptic track out, through
// batch's per-film runner (film_runner.h: the same steps as child processes,
// the same step reuse, atomic renames and failure records).
//
//   MakeOptions opt;  opt.film = "film.mp4";
//   MakeResult r = RunMake(opt, &observer);   // film.camera.csv + film.haptic.csv
//
// Outputs go beside the film or in opt.out_dir; the state that lets a second
// run reuse the camera path (step stamps: the film's sampled content hash and
// the estimate settings key, content_hash.h and batch_options.h) and the
// steps' logs live in <output folder>/.hapcine/<film id>/.

#include <string>
#include <vector>

#include "batch/film_runner.h"

namespace hapcine::batch {

// The hidden folder beside the outputs that holds make's per-film state.
constexpr const char* kMakeStateDir = ".hapcine";

struct MakeOptions {
  std::string film;     // the video, image folder or pattern
  std::string out_dir;  // empty: the film's folder
  std::string model = "cinematic";
  std::vector<std::string> estimate_args;  // words for `hapcine estimate`
  std::vector<std::string> haptics_args;   // words for `hapcine haptics` (not --model/-o/--hjif)
  bool hjif = false, preview = false, plot = false;
  bool force = false;    // redo every step
  bool use_edits = true;  // honour <stem>.edits.json (film_runner.h FindEditsFile)
  std::string step_exe;  // empty: this executable
};

struct MakeResult {
  FilmOutcome outcome;  // status kDone or kSkipped (failures throw)
  FilmLayout layout;    // where each file went
};

// The layout of `film`'s outputs: <stem>.camera.csv, <stem>.haptic.csv,
// <stem>.hjif, <stem>.preview.mp4, <stem>.camera.png, <stem>.haptic.png;
// the edits file: <stem>.edits.json beside the outputs, else beside the film.
FilmLayout MakeLayout(const MakeOptions& options, const FilmPlan& film);

// Step names in run order, for a progress display.
std::vector<std::string> MakeStepNames(const FilmLayout& layout);

// The BatchOptions the runner gets for these make options.
BatchOptions MakeBatchOptions(const MakeOptions& options);

// True for an image folder or a printf pattern ("plates/plate.%04d.exr").
bool IsImageSequenceInput(const std::string& film);

// Throws UsageError for options that do not apply to this film: --preview of
// an image sequence (no film to draw on), --fps among the estimate options of
// a video (its times come from its timestamps).
void CheckMakeOptions(const MakeOptions& options);

// The film's plan: absolute path, id, stem, sampled content hash. Throws
// Error(film, reason) for a missing, unreadable, non-regular or empty file.
// An image folder or pattern (docs/extract.md) is a film too: its stem is
// the folder's name or the pattern's text before the number ("plate"), its
// content the names and sizes of its images plus the sampled hash of the
// first and last.
FilmPlan MakeFilmPlan(const std::string& film);

// Runs (or reuses) the steps. Throws Error(film, reason) when a step fails,
// the reason being the step's own one line without its "hapcine <cmd>:
// <file>:" prefix; the outputs of steps that finished stay (each complete),
// nothing half-written is left.
MakeResult RunMake(const MakeOptions& options, FilmObserver* observer);

// "estimate: exit 1: hapcine estimate: /a/film.mp4: not a media file" ->
// "not a media file (estimate step)". Exposed for tests.
std::string StepFailureReason(const std::string& reason, const std::string& film);

}  // namespace hapcine::batch
