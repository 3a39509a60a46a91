// hapcine convert: camera paths to and from other tools' formats.
//   IN.camera.csv --to-tum OUT.txt                    (for evo)
//   IN.camera.csv --to-kitti|--to-nuke-chan|--to-blender OUT   (post-production)
//   --from-tum IN.txt --fov DEG -o OUT.camera.csv     (back from evo/SLAM tools)
//   --from-colmap DIR --times-from VIDEO_OR_CAMERA_CSV -o OUT.camera.csv
// Formats and the COLMAP axis mapping: docs/formats.md.


#include <cstdio>
#include <optional>
#include <iostream>
#include <vector>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "datasets/camera_exports.h"
#include "datasets/tum_format.h"
#include "datasets/colmap_text.h"
#include "extract/frame_source.h"

namespace hapcine::cli {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

struct FrameTimes {
  std::vector<double> time_s;  // by frame index 0..n-1
  int width = 0;
  int height = 0;
  double fps = 0;
};

// Presentation times of every frame: from a camera path (its frame/time_s
// columns and width/height/fps metadata), or by decoding a video.
FrameTimes ReadFrameTimes(const std::string& file) {
  FrameTimes times;
  if (EndsWith(file, ".csv")) {
    const CameraPath p = ReadCameraPathFile(file);
    for (const auto& f : p.frames) {
      if (f.frame != static_cast<int>(times.time_s.size())) {
        throw Error(file, "frames are not numbered 0, 1, 2, ... without gaps (frame " +
                              std::to_string(f.frame) + "); cannot use it as a frame timing");
      }
      times.time_s.push_back(f.time_s);
    }
    times.width = p.width();
    times.height = p.height();
    times.fps = p.fps();
    return times;
  }
  FrameSourceOptions o;
  o.max_working_side = 64;  // only the timestamps matter; decode small
  o.want_color = false;
  auto source = OpenFrameSource(file, o);
  const VideoInfo& info = source->info();
  times.width = info.width;
  times.height = info.height;
  times.fps = info.fps;
  Progress progress(std::cerr, ProgressModeFor(false), "reading frame times", "frames");
  Frame frame;
  long n = 0;
  while (source->Next(&frame)) {
    if (frame.index != static_cast<int>(times.time_s.size())) {
      throw Error(file, "decoder skipped to frame " + std::to_string(frame.index));
    }
    times.time_s.push_back(frame.time_s);
    progress.Update(static_cast<double>(++n), static_cast<double>(info.frame_count));
  }
  progress.Close();
  if (times.time_s.empty()) throw Error(file, "no frames decoded");
  return times;
}


struct ExportRequest {
  std::string input;
  std::string to_tum, to_kitti, to_chan, to_blender;
  std::optional<int> shot;
  std::optional<double> sensor_width_mm;  // --sensor-width-mm, else the header, else 36
  int start_frame = 1;
};

// The file each shot goes to: the name as given for one shot, else one
// file per shot (OUT.shot003.txt) so that no trajectory jumps at a cut.
std::vector<std::string> PerShotTargets(const std::string& file,
                                        const std::vector<ShotFrames>& shots) {
  if (shots.size() == 1) return {file};
  if (ResolveOutputTarget(file).direct) {
    throw UsageError(file + " is a device or FIFO and the path has " +
                     std::to_string(shots.size()) + " shots: choose one with --shot N");
  }
  std::vector<std::string> names;
  for (const ShotFrames& s : shots) names.push_back(PerShotFileName(file, s.shot));
  return names;
}

double SensorWidthMm(const ExportRequest& request, const CameraPath& path) {
  if (request.sensor_width_mm) return *request.sensor_width_mm;
  const auto it = path.metadata.find("sensor_width_mm");
  if (it == path.metadata.end()) return 36;
  char* end = nullptr;
  const double mm = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !(mm > 0 && mm <= 1000)) {
    throw Error(request.input, "header sensor_width_mm='" + it->second +
                                   "' is not a width in (0, 1000] mm");
  }
  return mm;
}

// Writes one shot's file in the format of the request.
void WriteShotFile(const ExportRequest& request, const CameraPath& path, const ShotFrames& shot,
                   const std::string& file) {
  AtomicFile out(file);
  if (!request.to_tum.empty()) {
    CameraPath one;
    one.frames = shot.frames;
    WriteTumTrajectory(one, out.stream());
  } else if (!request.to_kitti.empty()) {
    WriteKittiPoses(KittiPoses(shot), out.stream());
  } else {
    if (path.width() <= 0 || path.height() <= 0) {
      throw Error(request.input, "no width/height in the header: a .chan's vertical field of "
                                 "view needs the frame's aspect ratio");
    }
    WriteNukeChan(NukeChanRows(shot, static_cast<double>(path.height()) / path.width(),
                               request.start_frame),
                  out.stream());
  }
  out.Commit();
}

// hapcine convert IN.camera.csv --to-...: every output is declared (and
// checked against the input) before any is written; all commit together.
int RunExport(const ExportRequest& request) {
  const CameraPath path = ReadCameraPathFile(request.input);
  const std::vector<ShotFrames> shots = SelectShots(path, request.shot, request.input);
  std::vector<std::string> files;
  if (!request.to_blender.empty()) {
    files = {request.to_blender};
  } else {
    const std::string& target = !request.to_tum.empty()     ? request.to_tum
                                : !request.to_kitti.empty() ? request.to_kitti
                                                            : request.to_chan;
    files = PerShotTargets(target, shots);
  }
  const char* option = !request.to_tum.empty()      ? "--to-tum"
                       : !request.to_kitti.empty()  ? "--to-kitti"
                       : !request.to_chan.empty()   ? "--to-nuke-chan"
                                                    : "--to-blender";
  std::vector<NamedPath> outputs;
  for (const std::string& f : files) outputs.push_back({f, option});
  OutputSet output_set({{request.input, "INPUT"}}, outputs);
  if (!request.to_blender.empty()) {
    BlenderExportOptions options;
    options.sensor_width_mm = SensorWidthMm(request, path);
    options.start_frame = request.start_frame;
    options.source = request.input;
    AtomicFile out(request.to_blender);
    WriteBlenderScript(path, shots, options, out.stream());
    out.Commit();
  } else {
    for (size_t i = 0; i < shots.size(); ++i) WriteShotFile(request, path, shots[i], files[i]);
  }
  output_set.CommitAll();
  for (const std::string& f : files) std::cerr << "wrote " << f << "\n";
  return kExitOk;
}

// A COLMAP text model as a camera path, timed by `times_from`.
CameraPath ImportColmap(const std::string& from_colmap, const std::string& times_from) {
  if (times_from.empty()) throw UsageError("--from-colmap needs --times-from");
  const FrameTimes times = ReadFrameTimes(times_from);
  ColmapReadOptions colmap;
  colmap.frame_times = times.time_s;
  colmap.decoded_width = times.width;
  if (times.fps > 0) colmap.fps = times.fps;
  CameraPath path = ReadColmapTextModel(from_colmap, colmap);
  if (times.width > 0) path.metadata["width"] = std::to_string(times.width);
  if (times.height > 0) path.metadata["height"] = std::to_string(times.height);
  if (times.fps > 0) path.metadata["fps"] = FormatDouble(times.fps);
  path.metadata["source"] = from_colmap;
  return path;
}

// The import options (everything but ExportRequest).
struct ImportArgs {
  std::string from_tum, from_colmap, times_from, output;
  double fov_deg = 0;
};

// --from-tum or --from-colmap -> -o OUT.camera.csv.
int RunImport(const ImportArgs& a, bool has_input) {
  std::vector<NamedPath> inputs = {{a.from_tum, "--from-tum"}, {a.times_from, "--times-from"}};
  if (!a.from_colmap.empty()) {
    for (const char* f : {"cameras.txt", "images.txt", "points3D.txt"})
      inputs.push_back({a.from_colmap + "/" + f, "--from-colmap"});
  }
  OutputSet outputs(inputs, {{a.output, "-o"}});
  if (has_input) throw UsageError("an input camera path is only used with --to-*");
  if (a.output.empty()) throw UsageError("imports need -o OUT.camera.csv");
  if (!a.from_tum.empty()) {
    if (!(a.fov_deg > 0 && a.fov_deg < 180)) throw UsageError("--fov must be in (0, 180) degrees");
    CameraPath path = CameraPathFromTum(ReadTumTrajectoryFile(a.from_tum), a.fov_deg);
    path.metadata["source"] = a.from_tum;
    WriteCameraPathFile(path, a.output);
    outputs.CommitAll();
  } else {
    const CameraPath path = ImportColmap(a.from_colmap, a.times_from);
    WriteCameraPathFile(path, a.output);
    outputs.CommitAll();
    int registered = 0;
    for (const auto& f : path.frames) registered += f.confidence.value_or(1) > 0;
    std::cerr << "converted " << registered << " registered frames of " << path.frames.size()
              << " (the others hold the previous pose, confidence 0)\n";
  }
  std::cerr << "wrote " << a.output << "\n";
  return kExitOk;
}

void AddImportOptions(CLI::App& app, ImportArgs* a) {
  app.add_option("--from-tum", a->from_tum, "read a TUM trajectory (needs --fov and -o)");
  app.add_option("--fov", a->fov_deg,
                 "horizontal field of view (degrees) for every frame of a TUM import "
                 "(TUM has no intrinsics)")
      ->check(FiniteRange(1, 179));
  app.add_option("--from-colmap", a->from_colmap,
                 "COLMAP text model folder (cameras.txt, images.txt, optional points3D.txt); "
                 "export a binary model with `colmap model_converter --output_type TXT`");
  app.add_option("--times-from", a->times_from,
                 "frame times for the COLMAP import: a *.camera.csv (its frame/time_s columns) "
                 "or the video (decoded once for its timestamps); frames COLMAP did not register "
                 "hold the previous pose with confidence 0");
  app.add_option("-o,--output", a->output, "output camera path (*.camera.csv) for the imports");
}

}  // namespace

int RunConvert(int argc, char** argv) {
  CLI::App app{"Convert camera paths to and from other tools' formats (docs/formats.md):\n"
               "  hapcine convert IN.camera.csv --to-tum OUT.txt\n"
               "  hapcine convert IN.camera.csv --to-kitti OUT.txt | --to-nuke-chan OUT.chan\n"
               "  hapcine convert IN.camera.csv --to-blender OUT.py [--sensor-width-mm 36]\n"
               "  hapcine convert --from-tum IN.txt --fov 60 -o OUT.camera.csv\n"
               "  hapcine convert --from-colmap DIR --times-from VIDEO|CAMERA_CSV -o OUT.camera.csv",
               argv[0]};
  ExportRequest request;
  int shot = -1;
  double sensor_width_mm = 36;
  app.add_option("input", request.input, "camera path to export (*.camera.csv), with --to-*");
  app.add_option("--to-tum", request.to_tum,
                 "write the TUM trajectory format (timestamp tx ty tz qx qy qz qw), for evo; "
                 "one file per shot (OUT.shot003.txt) when the path has several");
  app.add_option("--to-kitti", request.to_kitti,
                 "write KITTI odometry poses (3x4 camera-to-world per row, camera x right, "
                 "y down, z forward, each shot from its first frame); one file per shot");
  app.add_option("--to-nuke-chan", request.to_chan,
                 "write a Nuke .chan (frame tx ty tz rx ry rz vertical_fov, rotation order "
                 "ZXY, Nuke's Camera default); one file per shot");
  app.add_option("--to-blender", request.to_blender,
                 "write a Python script for `blender --background --python OUT.py`: one "
                 "animated camera per shot, lens per frame, the scene's fps");
  app.add_option("--shot", shot, "export only this shot (its `shot` column value), to OUT as named")
      ->check(FiniteRange(0, 1e9));
  auto* sensor_option = app.add_option(
      "--sensor-width-mm", sensor_width_mm,
      "sensor width for the Blender lens (mm); default: the header's sensor_width_mm, else 36")
      ->check(FiniteRange(0.1, 1000));
  app.add_option("--start-frame", request.start_frame,
                 "frame number of the camera path's frame 0 in Blender and .chan exports")
      ->check(FiniteRange(0, 1e6));  // Blender's frames run from 0 to about 1e6
  ImportArgs import;
  AddImportOptions(app, &import);

  return RunApp(app, argc, argv, [&]() {
    const int exports = !request.to_tum.empty() + !request.to_kitti.empty() +
                        !request.to_chan.empty() + !request.to_blender.empty();
    const int modes = exports + !import.from_tum.empty() + !import.from_colmap.empty();
    if (modes != 1) {
      throw UsageError("choose exactly one of --to-tum, --to-kitti, --to-nuke-chan, "
                       "--to-blender, --from-tum, --from-colmap");
    }
    if (exports == 0) return RunImport(import, !request.input.empty());
    if (request.input.empty()) throw UsageError("exports need an input camera path");
    if (shot >= 0) request.shot = shot;
    if (sensor_option->count() > 0) request.sensor_width_mm = sensor_width_mm;
    return RunExport(request);
  });
}

}  // namespace hapcine::cli
