// Extract speed: decode-only vs decode + shot detection + KLT tracking.
//   hapcine_extract_bench <video> [--threads N] [--side PX] [--tracks N] [--cv-threads N]
//   [--color-side PX] [--skip-loop-filter] [--decode-only] [--klt-window N]
//   [--coarse-iterations N] [--coarse-step PX]
// Prints frames, wall time and ms/frame for decoding (scaling included) and
// for decoding + tracking, so the tracking overhead can be read directly.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <opencv2/core.hpp>
#include <string>

#include "core/error.h"
#include "extract/feature_tracker.h"
#include "extract/frame_source.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s <video> [--threads N] [--side PX] [--tracks N] [--cv-threads N] "
                 "[--color-side PX] [--skip-loop-filter] [--decode-only] [--klt-window N] "
                 "[--coarse-iterations N] [--coarse-step PX]\n",
                 argv[0]);
    return 2;
  }
  hapcine::FrameSourceOptions source_options;
  hapcine::TrackerOptions tracker_options;
  bool decode_only = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc)
      source_options.decode_threads = std::atoi(argv[++i]);
    else if (a == "--side" && i + 1 < argc)
      source_options.max_working_side = std::atoi(argv[++i]);
    else if (a == "--tracks" && i + 1 < argc)
      tracker_options.max_tracks = std::atoi(argv[++i]);
    else if (a == "--klt-window" && i + 1 < argc)
      tracker_options.klt_window = std::atoi(argv[++i]);
    else if (a == "--coarse-iterations" && i + 1 < argc)
      tracker_options.klt_coarse_iterations = std::atoi(argv[++i]);
    else if (a == "--coarse-step" && i + 1 < argc)
      tracker_options.klt_coarse_step_px = std::atof(argv[++i]);
    else if (a == "--color-side" && i + 1 < argc)
      source_options.color_max_side = std::atoi(argv[++i]);
    else if (a == "--skip-loop-filter")
      source_options.skip_loop_filter = true;
    else if (a == "--cv-threads" && i + 1 < argc)
      cv::setNumThreads(std::atoi(argv[++i]));
    else if (a == "--decode-only")
      decode_only = true;
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  try {
    auto t0 = std::chrono::steady_clock::now();
    auto source = hapcine::OpenFrameSource(argv[1], source_options);
    hapcine::FeatureTracker tracker(tracker_options);
    hapcine::Frame frame;
    long frames = 0, points = 0;
    double track_s = 0;
    while (source->Next(&frame)) {
      ++frames;
      if (decode_only) continue;
      const auto t1 = std::chrono::steady_clock::now();
      points += static_cast<long>(tracker.Process(frame).points.size());
      track_s += Seconds(t1);
    }
    const double total_s = Seconds(t0);
    const auto& info = source->info();
    std::printf("%s %dx%d %s working<=%d threads=%d: %ld frames, %s %.2f s = %.2f ms/frame",
                argv[1], info.width, info.height, info.codec.c_str(),
                source_options.max_working_side, source_options.decode_threads, frames,
                decode_only ? "decode" : "decode+track", total_s, 1000 * total_s / frames);
    if (!decode_only)
      std::printf(" (tracking alone %.2f ms/frame, %.0f tracks/frame)", 1000 * track_s / frames,
                  static_cast<double>(points) / frames);
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
