#include "batch/make.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "batch/content_hash.h"
#include "batch/library.h"
#include "core/error.h"
#include "core/hash.h"

namespace hapcine::batch {
namespace fs = std::filesystem;

FilmLayout MakeLayout(const MakeOptions& options, const FilmPlan& film) {
  FilmLayout layout;
  // Beside the film; for an image folder or pattern, beside the images'
  // folder (files added among the images would join the sequence).
  const fs::path film_path(film.path);
  const fs::path beside = film.path.find('%') != std::string::npos
                              ? film_path.parent_path().parent_path()
                              : film_path.parent_path();
  layout.output_dir = options.out_dir.empty() ? beside.string()
                                              : fs::absolute(options.out_dir).lexically_normal().string();
  layout.state_dir = (fs::path(layout.output_dir) / kMakeStateDir / film.id).string();
  layout.camera = film.stem + ".camera.csv";
  layout.models.push_back(
      {options.model, film.stem + ".haptic.csv", options.hjif ? film.stem + ".hjif" : ""});
  if (options.preview) layout.preview = film.stem + ".preview.mp4";
  if (options.plot) {
    layout.camera_plot = film.stem + ".camera.png";
    layout.haptic_plot = film.stem + ".haptic.png";
  }
  // Beside the outputs (with -o DIR: where a studio serving them saves), then beside the film.
  // Beside a video, its whole file stem (EditsPathForFilm's name, even where
  // the output stem is cut to fit 255 bytes).
  const std::string own_stem = IsImageSequenceInput(film.path) ? film.stem : FileStem(film.path);
  FindEditsFile(MakeBatchOptions(options),
                {(fs::path(layout.output_dir) / (film.stem + ".edits.json")).string(),
                 (beside / (own_stem + ".edits.json")).string()},
                &layout);
  return layout;
}

std::vector<std::string> MakeStepNames(const FilmLayout& layout) {
  std::vector<std::string> names = {"estimate"};
  for (const ModelOutputs& m : layout.models) names.push_back("haptics-" + m.model);
  if (!layout.preview.empty()) names.push_back("preview");
  if (!layout.camera_plot.empty()) names.push_back("plot-camera");
  if (!layout.haptic_plot.empty()) names.push_back("plot-haptic");
  return names;
}

BatchOptions MakeBatchOptions(const MakeOptions& options) {
  BatchOptions b;
  b.library = options.film;
  b.out_dir = options.out_dir.empty() ? "." : options.out_dir;
  b.jobs = 1;
  b.models = {options.model};
  b.estimate_args = options.estimate_args;
  b.haptics_args = options.haptics_args;
  b.step_exe = options.step_exe;
  b.force = options.force;
  b.hjif = options.hjif;
  b.preview = options.preview;
  b.plot = options.plot;
  b.use_edits = options.use_edits;
  return b;
}

bool IsImageSequenceInput(const std::string& film) {
  std::error_code ec;
  return film.find('%') != std::string::npos || fs::is_directory(film, ec);
}

namespace {

// An image folder's or pattern's identity: the names and sizes of the
// regular files in its folder (a pattern: those whose names have its text
// before the number, then a digit), plus the sampled hash of the first and last of them.
// Reading every image of a plate would take minutes; an edit that keeps
// every size and spares both ends goes unseen (--force).
ContentId SequenceContentId(const std::string& film) {
  const bool pattern = film.find('%') != std::string::npos;
  const fs::path dir = pattern ? fs::path(film).parent_path() : fs::path(film);
  const std::string name = fs::path(film).filename().string();
  const std::string head = pattern ? name.substr(0, name.find('%')) : "";
  std::vector<std::pair<std::string, uint64_t>> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir.empty() ? fs::path(".") : dir, ec)) {
    const std::string file = e.path().filename().string();
    // A pattern's images have a digit after the text before the number
    // (make's own outputs beside them, "plate.camera.csv", do not).
    const bool numbered = !pattern || (file.compare(0, head.size(), head) == 0 &&
                                       file.size() > head.size() &&
                                       std::isdigit(static_cast<unsigned char>(file[head.size()])));
    if (numbered && e.is_regular_file(ec)) files.emplace_back(e.path().string(), e.file_size(ec));
  }
  if (ec) throw Error(film, "cannot list the image folder (" + ec.message() + ")");
  if (files.empty()) throw Error(film, "no image files");
  std::sort(files.begin(), files.end());
  Fnv1a64 hash;
  ContentId id;
  for (const auto& [path, bytes] : files) {
    hash.Update(fs::path(path).filename().string() + "\n" + std::to_string(bytes) + "\n");
    id.size_bytes += bytes;
  }
  hash.Update(SampledContentId(files.front().first).hash + SampledContentId(files.back().first).hash);
  id.hash = "fnv1a64seq:" + hash.Hex();
  return id;
}

// "plate.%04d.png" -> "plate", "plates/" -> "plates".
std::string SequenceStem(const std::string& absolute) {
  std::string name = fs::path(absolute).filename().string();
  if (absolute.find('%') == std::string::npos) return name;
  name = name.substr(0, name.find('%'));
  while (!name.empty() && (name.back() == '.' || name.back() == '_' || name.back() == '-')) name.pop_back();
  return name.empty() ? fs::path(absolute).parent_path().filename().string() : name;
}

}  // namespace

FilmPlan MakeFilmPlan(const std::string& film) {
  FilmPlan plan;
  const bool sequence = IsImageSequenceInput(film);
  // A folder's path without its trailing '/': its name is the stem.
  plan.path = fs::absolute(film).lexically_normal().string();
  if (plan.path.size() > 1 && plan.path.back() == '/') plan.path.pop_back();
  plan.id = FilmId(plan.path);
  plan.stem = OutputStem(sequence ? SequenceStem(plan.path) : FileStem(plan.path), {});
  const ContentId id = sequence ? SequenceContentId(film) : SampledContentId(film);  // Error(film, reason)
  if (id.size_bytes == 0) throw Error(film, "empty file (0 bytes)");
  plan.size_bytes = id.size_bytes;
  plan.input_hash = id.hash;
  return plan;
}

std::string StepFailureReason(const std::string& reason, const std::string& film) {
  std::string step, text = reason;
  // "<step>: ..." (a step name has no '/' nor space; a folder error has)
  if (const size_t colon = text.find(": ");
      colon != std::string::npos && text.find_first_of("/ ") > colon) {
    step = text.substr(0, colon);
    text = text.substr(colon + 2);
  }
  // "exit 1: " (a signal's reason is kept: it says what happened)
  if (text.rfind("exit ", 0) == 0) {
    if (const size_t colon = text.find(": "); colon != std::string::npos) text = text.substr(colon + 2);
  }
  if (text.rfind("hapcine ", 0) == 0) {
    if (const size_t colon = text.find(": "); colon != std::string::npos) text = text.substr(colon + 2);
  }
  const std::string absolute = fs::absolute(film).lexically_normal().string();
  for (const std::string& name : {absolute, film}) {
    if (text.rfind(name + ": ", 0) == 0) {
      text = text.substr(name.size() + 2);
      break;
    }
  }
  return step.empty() ? text : text + " (" + step + " step)";
}

void CheckMakeOptions(const MakeOptions& options) {
  const bool sequence = IsImageSequenceInput(options.film);
  if (options.preview && sequence)
    throw UsageError("--preview needs a video file; an image sequence has no film to draw on");
  for (const std::string& a : options.estimate_args) {
    if (!sequence && (a == "--fps" || a.rfind("--fps=", 0) == 0))
      throw UsageError("--fps is for image folders and patterns; a video's times come from its timestamps");
  }
}

MakeResult RunMake(const MakeOptions& options, FilmObserver* observer) {
  CheckMakeOptions(options);
  const FilmPlan film = MakeFilmPlan(options.film);
  MakeResult result;
  result.layout = MakeLayout(options, film);
  const BatchOptions batch = MakeBatchOptions(options);
  batch.Check();
  result.outcome = RunFilm(batch, batch.ResolvedStepExe(), SettingsHash(batch), film,
                           result.layout, observer);
  if (result.outcome.status == FilmStatus::kBusy) {
    throw Error(options.film, "another hapcine make is working on this film (" +
                                  result.layout.state_dir + ")");
  }
  if (result.outcome.status == FilmStatus::kFailed) {
    throw Error(options.film, StepFailureReason(result.outcome.reason, options.film));
  }
  return result;
}

}  // namespace hapcine::batch
