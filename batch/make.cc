#include "batch/make.h"

#include <filesystem>

#include "batch/content_hash.h"
#include "batch/library.h"
#include "core/error.h"

namespace hapcine::batch {
namespace fs = std::filesystem;

FilmLayout MakeLayout(const MakeOptions& options, const FilmPlan& film) {
  FilmLayout layout;
  const fs::path film_path(film.path);
  layout.output_dir = options.out_dir.empty() ? film_path.parent_path().string()
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
  return b;
}

FilmPlan MakeFilmPlan(const std::string& film) {
  FilmPlan plan;
  plan.path = fs::absolute(film).lexically_normal().string();
  plan.id = FilmId(plan.path);
  plan.stem = OutputStem(FileStem(plan.path), {});
  const ContentId id = SampledContentId(film);  // throws Error(film, reason)
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

MakeResult RunMake(const MakeOptions& options, FilmObserver* observer) {
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
