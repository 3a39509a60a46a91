// hapcine plot: camera paths and haptic tracks as PNG (OpenCV) and SVG
// (written by hand), from one Figure description (datasets/plot_figure.h).

#include <iostream>

#include "cli/command.h"
#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "datasets/plot_png.h"
#include "datasets/plot_tracks.h"
#include "datasets/svg_writer.h"

namespace hapcine::cli {
namespace {

void WriteOutputs(const Figure& fig, const std::string& prefix, const std::string& format) {
  if (format == "png" || format == "both") {
    WriteFigurePngFile(fig, prefix + ".png");
    std::cerr << "wrote " << prefix << ".png\n";
  }
  if (format == "svg" || format == "both") {
    WriteFigureSvgFile(fig, prefix + ".svg");
    std::cerr << "wrote " << prefix << ".svg\n";
  }
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
    sub->add_option("-o,--output", prefix, "output prefix: writes PREFIX.png and/or PREFIX.svg")
        ->required();
    sub->add_option("--format", format, "png, svg or both")
        ->capture_default_str()->check(CLI::IsMember({"png", "svg", "both"}));
    sub->add_option("--width", width_px, "figure width in pixels")
        ->capture_default_str()->check(CLI::Range(300, 10000));
    sub->add_option("--title", title, "figure title (default: the input file names)");
  };

  std::string gt_file, est_file;
  bool absolute = false, no_scale = false;
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
  add_common(camera);

  std::string track_file;
  CLI::App* haptic = app.add_subcommand(
      "haptic",
      "actuator displacements (head, left hand, right hand; x/y/z in mm) over time, with the "
      "`effect` column as labelled bands (the paper's Figure 4)");
  haptic->add_option("track", track_file, "haptic track (*.haptic.csv)")
      ->required();
  add_common(haptic);

  return RunApp(app, argc, argv, [&]() {
    Figure fig;
    if (camera->parsed()) {
      const CameraPath gt = ReadCameraPathFile(gt_file);
      CameraPath est;
      if (!est_file.empty()) est = ReadCameraPathFile(est_file);
      CameraPlotOptions opt;
      opt.relative_to_first = !absolute;
      opt.scale_estimate = !absolute && !no_scale;
      opt.title = title.empty() ? gt_file + (est_file.empty() ? "" : "  vs  " + est_file) : title;
      fig = CameraPathFigure(gt, est_file.empty() ? nullptr : &est, opt);
    } else {
      const HapticTrack track = ReadHapticTrackFile(track_file);
      fig = HapticTrackFigure(track, title.empty() ? track_file + " (" + track.model + ")" : title);
    }
    fig.width_px = width_px;
    WriteOutputs(fig, prefix, format);
    return kExitOk;
  });
}

}  // namespace hapcine::cli
