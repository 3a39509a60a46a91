// hapcine plot: camera paths and haptic tracks as PNG (OpenCV) and SVG
// (written by hand), from one Figure description (datasets/plot_figure.h).

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "core/output_files.h"
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

// Platform tracks overlaid; legend names as for haptic tracks (the
// platform's name, or the file's stem when two tracks share it).
Figure PlatformFigureFromFiles(const std::vector<std::string>& files, const std::string& title) {
  std::vector<PlatformTrack> tracks;
  std::string names;
  for (const std::string& f : files) {
    tracks.push_back(ReadPlatformTrackFile(f));
    names += (names.empty() ? "" : "  vs  ") + f;
  }
  std::vector<const PlatformTrack*> ptrs;
  std::vector<std::string> legend;
  for (size_t i = 0; i < tracks.size(); ++i) {
    ptrs.push_back(&tracks[i]);
    bool shared = false;
    for (size_t j = 0; j < tracks.size(); ++j) shared |= j != i && tracks[j].platform == tracks[i].platform;
    legend.push_back(shared ? FileStem(files[i]) : tracks[i].platform);
  }
  return PlatformTracksFigure(ptrs, title.empty() ? names : title, legend);
}

}  // namespace

int RunPlot(int argc, char** argv) {
  CLI::App app{"Draw camera paths and haptic tracks as PNG and SVG (OUT_PREFIX.png, "
               "OUT_PREFIX.svg).",
               argv[0]};
  app.require_subcommand(1);
  std::string prefix, format = "both", title;
  int width_px = 1200;
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("-o,--output", prefix,
                    "output prefix: writes PREFIX.png and/or PREFIX.svg (a trailing .png or .svg "
                    "is the prefix's; with one --format, a device or FIFO is written as named)")
        ->required();
    sub->add_option("--format", format, "png, svg or both")
        ->capture_default_str()->check(CLI::IsMember({"png", "svg", "both"}));
    sub->add_option("--width", width_px, "figure width in pixels")
        ->capture_default_str()
        ->check(FiniteRange(300, 10000));
    sub->add_option("--title", title, "figure title (default: the input file names)");
  };

  std::string gt_file, est_file;
  bool absolute = false, no_scale = false, no_effects = false;
  CLI::App* camera = app.add_subcommand(
      "camera",
      "pan/tilt/roll (deg), camera centre x/y/z and horizontal FOV over time; with a second "
      "path, the estimate is drawn dashed over the ground truth");
  camera->add_option("gt", gt_file, "camera path (*.camera.csv), e.g. the ground truth")
      ->required();
  camera->add_option("est", est_file, "optional second camera path (the estimate)");
  camera->add_flag("--absolute", absolute,
                   "plot poses as stored instead of relative to each path's first frame");
  camera->add_flag("--no-scale", no_scale,
                   "do not scale the estimate's positions onto the first path (least squares)");
  camera->add_flag("--no-effects", no_effects,
                   "no time line of the effects the classifier finds in each path");
  add_common(camera);

  std::vector<std::string> track_files;
  CLI::App* haptic = app.add_subcommand(
      "haptic",
      "actuator displacements (head, left hand, right hand; x/y/z in mm) over time, with the "
      "`effect` column as labelled bands; several tracks are overlaid (the first solid, the "
      "others dashed), e.g. the cinematic and semantic tracks of a clip as in the paper's "
      "Figure 4");
  haptic->add_option("tracks", track_files, "haptic tracks (*.haptic.csv), one or more")
      ->required();
  add_common(haptic);

  std::vector<std::string> platform_files;
  CLI::App* platform = app.add_subcommand(
      "platform",
      "motion platform poses (sway/heave/surge in mm, pitch/yaw/roll in degrees) and Stewart "
      "leg extensions over time; several tracks overlaid (the first solid, the others dashed)");
  platform->add_option("tracks", platform_files, "platform tracks (*.platform.csv), one or more")
      ->required();
  add_common(platform);

  return RunApp(app, argc, argv, [&]() {
    const bool single = format != "both";
    const std::string png = format != "svg" ? PlotOutputPath(prefix, "png", single) : "";
    const std::string svg = format != "png" ? PlotOutputPath(prefix, "svg", single) : "";
    std::vector<NamedPath> inputs;
    if (camera->parsed()) {
      inputs = {{gt_file, "GT"}, {est_file, "EST"}};
    } else {
      for (const std::string& f : platform->parsed() ? platform_files : track_files)
        inputs.push_back({f, "TRACK"});
    }
    OutputSet outputs(inputs,
                      {{png, "-o"}, {svg, "-o"}});
    Figure fig;
    if (camera->parsed()) {
      const CameraPath gt = ReadCameraPathFile(gt_file);
      CameraPath est;
      if (!est_file.empty()) est = ReadCameraPathFile(est_file);
      CameraPlotOptions opt;
      opt.relative_to_first = !absolute;
      opt.scale_estimate = !absolute && !no_scale;
      opt.effect_labels = !no_effects;
      opt.title = title.empty() ? gt_file + (est_file.empty() ? "" : "  vs  " + est_file) : title;
      fig = CameraPathFigure(gt, est_file.empty() ? nullptr : &est, opt);
    } else if (platform->parsed()) {
      fig = PlatformFigureFromFiles(platform_files, title);
    } else {
      std::vector<HapticTrack> tracks;
      std::string names;
      for (const std::string& f : track_files) {
        tracks.push_back(ReadHapticTrackFile(f));
        names += (names.empty() ? "" : "  vs  ") + f + " (" + tracks.back().model + ")";
      }
      std::vector<const HapticTrack*> ptrs;
      for (const HapticTrack& t : tracks) ptrs.push_back(&t);
      // Legend names: the model, or the file's stem (no folder, no
      // .haptic.csv) when two tracks share a model.
      std::vector<std::string> legend;
      for (size_t i = 0; i < tracks.size(); ++i) {
        bool shared = false;
        for (size_t j = 0; j < tracks.size(); ++j) {
          shared |= j != i && tracks[j].model == tracks[i].model;
        }
        legend.push_back(shared ? FileStem(track_files[i]) : tracks[i].model);
      }
      fig = HapticTracksFigure(ptrs, title.empty() ? names : title, legend);
    }
    fig.width_px = width_px;
    WriteOutputs(fig, png, svg);
    outputs.CommitAll();
    for (const std::string& written : {png, svg}) {
      if (!written.empty()) std::cerr << "wrote " << written << "\n";
    }
    return kExitOk;
  });
}

}  // namespace hapcine::cli
