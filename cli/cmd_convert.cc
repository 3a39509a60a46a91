// hapcine convert: camera paths to and from other tools' formats.
//   IN.camera.csv --to-tum OUT.txt                    (for evo)
//   --from-tum IN.txt --fov DEG -o OUT.camera.csv     (back from evo/SLAM tools)
//   --from-colmap DIR --times-from VIDEO_OR_CAMERA_CSV -o OUT.camera.csv
// Formats and the COLMAP axis mapping: docs/formats.md.


#include <cstdio>
#include <iostream>
#include <vector>

#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/camera_path.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/progress.h"
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

}  // namespace

int RunConvert(int argc, char** argv) {
  CLI::App app{"Convert camera paths to and from other tools' formats (docs/formats.md):\n"
               "  hapcine convert IN.camera.csv --to-tum OUT.txt\n"
               "  hapcine convert --from-tum IN.txt --fov 60 -o OUT.camera.csv\n"
               "  hapcine convert --from-colmap DIR --times-from VIDEO|CAMERA_CSV -o OUT.camera.csv",
               argv[0]};
  std::string input, to_tum, from_tum, from_colmap, times_from, output;
  double fov_deg = 0;
  app.add_option("input", input, "camera path to convert (*.camera.csv), with --to-tum");
  app.add_option("--to-tum", to_tum,
                 "write the TUM trajectory format (timestamp tx ty tz qx qy qz qw), for evo");
  app.add_option("--from-tum", from_tum, "read a TUM trajectory (needs --fov and -o)");
  app.add_option("--fov", fov_deg,
                 "horizontal field of view (degrees) for every frame of a TUM import "
                 "(TUM has no intrinsics)")
      ->check(FiniteRange(1, 179));
  app.add_option("--from-colmap", from_colmap,
                 "COLMAP text model folder (cameras.txt, images.txt, optional points3D.txt); "
                 "export a binary model with `colmap model_converter --output_type TXT`");
  app.add_option("--times-from", times_from,
                 "frame times for the COLMAP import: a *.camera.csv (its frame/time_s columns) "
                 "or the video (decoded once for its timestamps); frames COLMAP did not register "
                 "hold the previous pose with confidence 0");
  app.add_option("-o,--output", output, "output camera path (*.camera.csv) for the imports");

  return RunApp(app, argc, argv, [&]() {
    const int modes = !to_tum.empty() + !from_tum.empty() + !from_colmap.empty();
    if (modes != 1) {
      throw UsageError("choose exactly one of --to-tum, --from-tum, --from-colmap");
    }
    std::vector<NamedPath> inputs = {
        {input, "INPUT"}, {from_tum, "--from-tum"}, {times_from, "--times-from"}};
    if (!from_colmap.empty()) {
      for (const char* f : {"cameras.txt", "images.txt", "points3D.txt"})
        inputs.push_back({from_colmap + "/" + f, "--from-colmap"});
    }
    OutputSet outputs(inputs, {{to_tum, "--to-tum"}, {output, "-o"}});
    if (!to_tum.empty()) {
      if (input.empty()) throw UsageError("--to-tum needs an input camera path");
      WriteTumTrajectoryFile(ReadCameraPathFile(input), to_tum);
      outputs.CommitAll();
      std::cerr << "wrote " << to_tum << "\n";
      return kExitOk;
    }
    if (!input.empty()) throw UsageError("an input camera path is only used with --to-tum");
    if (output.empty()) throw UsageError("imports need -o OUT.camera.csv");
    if (!from_tum.empty()) {
      if (!(fov_deg > 0 && fov_deg < 180)) throw UsageError("--fov must be in (0, 180) degrees");
      CameraPath path = CameraPathFromTum(ReadTumTrajectoryFile(from_tum), fov_deg);
      path.metadata["source"] = from_tum;
      WriteCameraPathFile(path, output);
      outputs.CommitAll();
    } else {
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
      WriteCameraPathFile(path, output);
      outputs.CommitAll();
      int registered = 0;
      for (const auto& f : path.frames) registered += f.confidence.value_or(1) > 0;
      std::cerr << "converted " << registered << " registered frames of " << path.frames.size()
                << " (the others hold the previous pose, confidence 0)\n";
    }
    std::cerr << "wrote " << output << "\n";
    return kExitOk;
  });
}

}  // namespace hapcine::cli
