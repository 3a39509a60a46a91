// hapcine plot: camera paths and haptic tracks as PNG (OpenCV) and SVG
// (written by hand), from one Figure description (datasets/plot_figure.h).

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/haptic_track.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "datasets/plot_pages.h"
#include "datasets/plot_platform.h"
#include "datasets/plot_png.h"
#include "datasets/plot_tracks.h"
#include "datasets/svg_writer.h"

namespace hapcine::cli {
namespace {

// Both files are complete under temporary names before either is renamed
// into place (the command's OutputSet): a failure leaves neither.
void WriteOutputs(const Figure& fig, const std::string& png_path, const std::string& svg_path) {
  std::unique_ptr<AtomicFile> png, svg;
  if (!png_path.empty()) {
    const std::vector<unsigned char> bytes = EncodeFigurePng(fig, png_path);
    png = std::make_unique<AtomicFile>(png_path);
    png->stream().write(reinterpret_cast<const char*>(bytes.data()),
                        static_cast<std::streamsize>(bytes.size()));
  }
  if (!svg_path.empty()) {
    svg = std::make_unique<AtomicFile>(svg_path);
    svg->stream() << RenderFigureSvg(fig);
  }
  for (auto* f : {png.get(), svg.get()}) {
    if (f) f->Commit();
  }
}

std::string FileStem(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  for (const char* suffix : {".haptic.csv", ".platform.csv", ".csv"}) {
    const std::string sfx = suffix;
    if (name.size() > sfx.size() && name.compare(name.size() - sfx.size(), sfx.size(), sfx) == 0) {
      return name.substr(0, name.size() - sfx.size());
    }
  }
  return name;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The file one format is written to. `-o fig` and `-o fig.png` both give
// fig.png (and fig.svg); with one format, `-o /dev/stdout` or a FIFO is
// written as named, since "/dev/null.png" is not what anyone asks for.
std::string PlotOutputPath(const std::string& prefix, const std::string& ext, bool single_format) {
  for (const char* known : {".png", ".svg"}) {
    if (EndsWith(prefix, known)) return prefix.substr(0, prefix.size() - 4) + "." + ext;
  }
  std::error_code ec;
  const auto status = std::filesystem::status(prefix, ec);
  const bool special = !ec && std::filesystem::exists(status) &&
                       !std::filesystem::is_regular_file(status) &&
                       !std::filesystem::is_directory(status);
  if (single_format && special) return prefix;
  return prefix + "." + ext;
}

// Legend names: each track's name (a haptic track's model, a platform's
// name), or the file's stem (no folder, no .haptic.csv) when two tracks
// share a name.
std::vector<std::string> LegendNames(const std::vector<std::string>& names,
                                     const std::vector<std::string>& files) {
  std::vector<std::string> legend;
  for (size_t i = 0; i < names.size(); ++i) {
    bool shared = false;
    for (size_t j = 0; j < names.size(); ++j) shared |= j != i && names[j] == names[i];
    legend.push_back(shared ? FileStem(files[i]) : names[i]);
  }
  return legend;
}

// The rows of `track` inside [from, to] and one on either side: a page of a
// two-hour track without copying the other pages' samples.
HapticTrack CropTrack(const HapticTrack& track, double from, double to) {
  HapticTrack out = track;
  out.samples.clear();
  auto before = [](const HapticSample& s, double t) { return s.time_s < t; };
  auto after = [](double t, const HapticSample& s) { return t < s.time_s; };
  auto begin = std::lower_bound(track.samples.begin(), track.samples.end(), from, before);
  auto end = std::upper_bound(track.samples.begin(), track.samples.end(), to, after);
  if (begin != track.samples.begin()) --begin;
  if (end != track.samples.end()) ++end;
  out.samples.assign(begin, end);
  return out;
}

// What the pages show: the command's choices of range and paging.
struct PageChoice {
  std::string from, to;     // as typed; "" = the data's ends
  double page_minutes = 0;  // 0 = one page
  bool per_shot = false;
};

std::vector<TimeRange> ChoosePages(const PageChoice& c, double first_s, double last_s,
                                   const std::vector<double>& cuts) {
  const double from = c.from.empty() ? first_s : ParsePlotTime(c.from, "--from");
  const double to = c.to.empty() ? last_s : ParsePlotTime(c.to, "--to");
  if (!(to > from)) throw UsageError("--to must come after --from (and after the data's start)");
  if (c.per_shot) return PagesByShot(from, to, cuts);
  return PagesByDuration(from, to, 60 * c.page_minutes);
}

void AddPageOptions(CLI::App* sub, PageChoice* pages) {
    sub->add_option("--from", pages->from,
                    "start of the plotted range: seconds (90.5) or running time (1:30, 1:02:03.5)");
    sub->add_option("--to", pages->to, "end of the plotted range (same forms as --from)");
    sub->add_option("--page-minutes", pages->page_minutes,
                    "cut the range into pages of this many minutes, written as PREFIX-001.png, "
                    "PREFIX-002.png, ... (a two-hour film stays readable)")
        ->check(FiniteRange(0.01, 1e5));
    sub->add_flag("--page-per-shot", pages->per_shot,
                  "one page per shot (the `shot` column), numbered as with --page-minutes")
        ->excludes("--page-minutes");
}

// The pages of one plot: their time ranges and how to draw one.
struct PlotPages {
  std::vector<TimeRange> ranges;
  std::function<Figure(const TimeRange&)> page;
};

// The camera figure is built once (relative poses, the classifier) and cropped per page.
PlotPages CameraPages(const std::string& gt_file, const std::string& est_file,
                      const CameraPlotOptions& opt, const PageChoice& choice) {
  const CameraPath gt = ReadCameraPathFile(gt_file);
  CameraPath est;
  if (!est_file.empty()) est = ReadCameraPathFile(est_file);
  auto whole = std::make_shared<Figure>(CameraPathFigure(gt, est_file.empty() ? nullptr : &est, opt));
  PlotPages pages;
  pages.ranges = ChoosePages(choice, gt.frames.front().time_s, gt.frames.back().time_s, whole->cut_x);
  pages.page = [whole](const TimeRange& r) { return CropFigure(*whole, r.first, r.second); };
  return pages;
}

// The tracks are cropped before the figure is built: a page of a two-hour
// 1 kHz track (7 million rows) copies only its own rows.
PlotPages HapticPages(const std::vector<std::string>& files, const std::string& camera_file,
                      const std::string& title, const PageChoice& choice) {
  auto tracks = std::make_shared<std::vector<HapticTrack>>();
  std::string names;
  for (const std::string& f : files) {
    tracks->push_back(ReadHapticTrackFile(f));
    names += (names.empty() ? "" : "  vs  ") + f + " (" + tracks->back().model + ")";
  }
  std::optional<PlotPanel> confidence;
  std::vector<double> cuts = ShotCutTimes(tracks->front());
  if (!camera_file.empty()) {
    const CameraPath path = ReadCameraPathFile(camera_file);
    confidence = ConfidencePanel(path, "estimate confidence");
    if (cuts.empty()) cuts = ShotCutTimes(path);
  }
  std::vector<std::string> models;
  for (const HapticTrack& t : *tracks) models.push_back(t.model);
  const std::vector<std::string> legend = LegendNames(models, files);
  const std::string fig_title = title.empty() ? names : title;
  PlotPages pages;
  pages.ranges = ChoosePages(choice, tracks->front().samples.front().time_s,
                             tracks->front().samples.back().time_s, cuts);
  pages.page = [tracks, confidence, cuts, legend, fig_title](const TimeRange& r) {
    std::vector<HapticTrack> cropped;
    for (const HapticTrack& t : *tracks) cropped.push_back(CropTrack(t, r.first, r.second));
    std::vector<const HapticTrack*> ptrs;
    for (const HapticTrack& t : cropped) ptrs.push_back(&t);
    Figure fig = HapticTracksFigure(ptrs, fig_title, legend);
    fig.cut_x = cuts;
    if (confidence) fig.panels.insert(fig.panels.begin() + kNumActuators, *confidence);
    return CropFigure(fig, r.first, r.second);
  };
  return pages;
}

// Platform tracks overlaid; legend names as for haptic tracks (the
// platform's name, or the file's stem when two tracks share it). Built once
// and cropped per page.
PlotPages PlatformPages(const std::vector<std::string>& files, const std::string& title,
                        const PageChoice& choice) {
  std::vector<PlatformTrack> tracks;
  std::string names;
  for (const std::string& f : files) {
    tracks.push_back(ReadPlatformTrackFile(f));
    if (tracks.back().samples.empty()) throw Error(f, "no samples");
    names += (names.empty() ? "" : "  vs  ") + f;
  }
  std::vector<const PlatformTrack*> ptrs;
  std::vector<std::string> platform_names;
  for (const PlatformTrack& t : tracks) {
    ptrs.push_back(&t);
    platform_names.push_back(t.platform);
  }
  const std::vector<std::string> legend = LegendNames(platform_names, files);
  auto whole = std::make_shared<Figure>(PlatformTracksFigure(ptrs, title.empty() ? names : title, legend));
  PlotPages pages;
  pages.ranges = ChoosePages(choice, tracks.front().samples.front().time_s,
                             tracks.front().samples.back().time_s, whole->cut_x);
  pages.page = [whole](const TimeRange& r) { return CropFigure(*whole, r.first, r.second); };
  return pages;
}

// Every page's files are complete before any is renamed into place.
void WritePages(const PlotPages& plot, const std::string& png, const std::string& svg,
                const std::vector<NamedPath>& inputs, int width_px) {
  const size_t n = plot.ranges.size();
  std::vector<std::pair<std::string, std::string>> files;  // png, svg per page
  std::vector<NamedPath> outputs;
  for (size_t i = 0; i < n; ++i) {
    files.push_back({png.empty() ? "" : PagePath(png, i, n), svg.empty() ? "" : PagePath(svg, i, n)});
    outputs.push_back({files.back().first, "-o"});
    outputs.push_back({files.back().second, "-o"});
  }
  OutputSet set(inputs, outputs);
  Progress progress(std::cerr, ProgressModeFor(n < 5), "plot", "pages");
  for (size_t i = 0; i < n; ++i) {
    Figure fig = plot.page(plot.ranges[i]);
    fig.width_px = width_px;
    if (n > 1) fig.title += "  [" + std::to_string(i + 1) + "/" + std::to_string(n) + "]";
    WriteOutputs(fig, files[i].first, files[i].second);
    progress.Update(static_cast<double>(i + 1), static_cast<double>(n));
  }
  set.CommitAll();
  progress.Finish(static_cast<double>(n));
  for (const auto& [page_png, page_svg] : files) {
    for (const std::string& written : {page_png, page_svg}) {
      if (!written.empty()) std::cerr << "wrote " << written << "\n";
    }
  }
}

// Every option of the three subcommands.
struct PlotArgs {
  std::string prefix, format = "both", title;
  int width_px = 1200;
  PageChoice pages;
  std::string gt_file, est_file;
  bool absolute = false, no_scale = false, no_effects = false;
  std::vector<std::string> track_files, platform_files;
  std::string confidence_file;
};

void AddCommonOptions(CLI::App* sub, PlotArgs* a) {
  sub->add_option("-o,--output", a->prefix,
                  "output prefix: writes PREFIX.png and/or PREFIX.svg (a trailing .png or .svg "
                  "is the prefix's; with one --format, a device or FIFO is written as named)")
      ->required();
  sub->add_option("--format", a->format, "png, svg or both")
      ->capture_default_str()->check(CLI::IsMember({"png", "svg", "both"}));
  sub->add_option("--width", a->width_px, "figure width in pixels")
      ->capture_default_str()
      ->check(FiniteRange(300, 10000));
  sub->add_option("--title", a->title, "figure title (default: the input file names)");
  AddPageOptions(sub, &a->pages);
}

CLI::App* AddCameraCommand(CLI::App& app, PlotArgs* a) {
  CLI::App* camera = app.add_subcommand(
      "camera",
      "pan/tilt/roll (deg), camera centre x/y/z and horizontal FOV over time; with a second "
      "path, the estimate is drawn dashed over the ground truth");
  camera->add_option("gt", a->gt_file, "camera path (*.camera.csv), e.g. the ground truth")
      ->required();
  camera->add_option("est", a->est_file, "optional second camera path (the estimate)");
  camera->add_flag("--absolute", a->absolute,
                   "plot poses as stored instead of relative to each path's first frame");
  camera->add_flag("--no-scale", a->no_scale,
                   "do not scale the estimate's positions onto the first path (least squares)");
  camera->add_flag("--no-effects", a->no_effects,
                   "no time line of the effects the classifier finds in each path");
  AddCommonOptions(camera, a);
  return camera;
}

CLI::App* AddHapticCommand(CLI::App& app, PlotArgs* a) {
  CLI::App* haptic = app.add_subcommand(
      "haptic",
      "actuator displacements (head, left hand, right hand; x/y/z in mm) over time, with the "
      "`effect` column as labelled bands; several tracks are overlaid (the first solid, the "
      "others dashed), e.g. the cinematic and semantic tracks of a clip as in the paper's "
      "Figure 4");
  haptic->add_option("tracks", a->track_files, "haptic tracks (*.haptic.csv), one or more")
      ->required();
  haptic->add_option("--camera", a->confidence_file,
                     "the camera path the tracks were made from: its `confidence` column as a "
                     "shaded panel under the curves, its `shot` column as cut lines when the "
                     "tracks have none");
  AddCommonOptions(haptic, a);
  return haptic;
}

CLI::App* AddPlatformCommand(CLI::App& app, PlotArgs* a) {
  CLI::App* platform = app.add_subcommand(
      "platform",
      "motion platform poses (sway/heave/surge in mm, pitch/yaw/roll in degrees) and Stewart "
      "leg extensions over time; several tracks overlaid (the first solid, the others dashed)");
  platform->add_option("tracks", a->platform_files, "platform tracks (*.platform.csv), one or more")
      ->required();
  AddCommonOptions(platform, a);
  return platform;
}

PlotPages CameraPlot(const PlotArgs& a, std::vector<NamedPath>* inputs) {
  *inputs = {{a.gt_file, "GT"}, {a.est_file, "EST"}};
  CameraPlotOptions opt;
  opt.relative_to_first = !a.absolute;
  opt.scale_estimate = !a.absolute && !a.no_scale;
  opt.effect_labels = !a.no_effects;
  opt.title =
      a.title.empty() ? a.gt_file + (a.est_file.empty() ? "" : "  vs  " + a.est_file) : a.title;
  return CameraPages(a.gt_file, a.est_file, opt, a.pages);
}

}  // namespace

int RunPlot(int argc, char** argv) {
  CLI::App app{"Draw camera paths and haptic tracks as PNG and SVG (OUT_PREFIX.png, "
               "OUT_PREFIX.svg).",
               argv[0]};
  app.require_subcommand(1);
  PlotArgs a;
  CLI::App* camera = AddCameraCommand(app, &a);
  AddHapticCommand(app, &a);
  CLI::App* platform = AddPlatformCommand(app, &a);
  return RunApp(app, argc, argv, [&]() {
    const bool single = a.format != "both";
    const std::string png = a.format != "svg" ? PlotOutputPath(a.prefix, "png", single) : "";
    const std::string svg = a.format != "png" ? PlotOutputPath(a.prefix, "svg", single) : "";
    std::vector<NamedPath> inputs;
    PlotPages plot;
    if (camera->parsed()) {
      plot = CameraPlot(a, &inputs);
    } else if (platform->parsed()) {
      for (const std::string& f : a.platform_files) inputs.push_back({f, "TRACK"});
      plot = PlatformPages(a.platform_files, a.title, a.pages);
    } else {
      for (const std::string& f : a.track_files) inputs.push_back({f, "TRACK"});
      inputs.push_back({a.confidence_file, "--camera"});
      plot = HapticPages(a.track_files, a.confidence_file, a.title, a.pages);
    }
    WritePages(plot, png, svg, inputs, a.width_px);
    return kExitOk;
  });
}

}  // namespace hapcine::cli
