// Fills the frames a keyframe-only camera path skipped (the COLMAP peer sees
// every Nth frame). Frames with confidence 0 (`hapcine convert --from-colmap`
// writes those for frames COLMAP did not register) count as skipped. Between two estimated frames at most --max-gap apart the
// pose is interpolated (slerp, linear centre, geometric focal); wider gaps
// and the ends stay empty, so `hapcine eval` counts them as not estimated.
//
//   hapcine_path_fill IN.camera.csv OUT.camera.csv --fps 24 [--max-gap 8]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/peer_convert.h"
#include "bench/peer_video.h"
#include "core/camera_path.h"
#include "core/error.h"

int main(int argc, char** argv) {
  using namespace hapcine;
  if (argc < 3 || std::string(argv[1]) == "--help") {
    std::printf("usage: %s IN.camera.csv OUT.camera.csv --fps 24 [--max-gap 8]\n", argv[0]);
    return argc < 3 ? 2 : 0;
  }
  try {
    const double fps = std::stod(bench::ArgValue(argc, argv, "--fps", "0"));
    const int max_gap = std::stoi(bench::ArgValue(argc, argv, "--max-gap", "8"));
    if (!(fps > 0) || max_gap < 1) throw UsageError("--fps must be > 0 and --max-gap >= 1");
    CameraPath in = ReadCameraPathFile(argv[1]);
    const size_t rows = in.frames.size();
    in.frames.erase(std::remove_if(in.frames.begin(), in.frames.end(),
                                   [](const CameraFrame& f) { return f.confidence && *f.confidence <= 0; }),
                    in.frames.end());
    if (in.frames.empty()) throw Error(argv[1], "no frame with a non-zero confidence");
    CameraPath out;
    out.metadata = in.metadata;
    out.metadata["fps"] = std::to_string(fps);
    for (size_t k = 0; k < in.frames.size(); ++k) {
      CameraFrame a = in.frames[k];
      a.time_s = a.frame / fps;
      out.frames.push_back(a);
      if (k + 1 == in.frames.size()) break;
      CameraFrame b = in.frames[k + 1];
      b.time_s = b.frame / fps;
      const int gap = b.frame - a.frame;
      if (gap > max_gap) continue;
      for (int f = a.frame + 1; f < b.frame; ++f) {
        CameraFrame m = bench::InterpolateFrames(a, b, double(f - a.frame) / gap);
        m.frame = f;
        m.time_s = f / fps;
        out.frames.push_back(m);
      }
    }
    WriteCameraPathFile(out, argv[2]);
    std::fprintf(stderr, "path_fill: %zu of %zu rows estimated -> %zu frames\n", in.frames.size(), rows,
                 out.frames.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_path_fill: %s\n", e.what());
    return 1;
  }
  return 0;
}
