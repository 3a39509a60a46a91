#include "estimate/colmap_backend.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "core/child_process.h"
#include "core/error.h"
#include "core/stop_signal.h"
#include "datasets/colmap_text.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

std::string SignalName(int sig) {
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  return "a stop request";
}

// Removes the temporary folder on every exit path, including SIGINT/SIGTERM
// (ScopedStopSignals turns them into an Error that unwinds to here).
struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "hapcine-colmap-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw Error(tmpl, "cannot create a temporary folder");
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

Error Interrupted(const VideoInfo& info, const std::string& during) {
  return Error(info.path, "interrupted by " + SignalName(StopSignal()) + " during " + during);
}

// Runs `colmap STEP ARGS...`, appending to one log for all steps; a failure
// or a stop request is an Error naming the video and the log's last line.
struct ColmapRunner {
  const VideoInfo& info;
  std::string binary, log;

  void Run(const std::string& step, std::vector<std::string> args) const {
    args.insert(args.begin(), {binary, step});
    ChildOptions options;
    options.append_log = true;       // one colmap.log for all steps
    options.stop_on_request = true;  // SIGINT/SIGTERM end the step (ScopedStopSignals)
    const ChildResult r = RunChild(args, log, options);
    if (r.stopped) throw Interrupted(info, "colmap " + step);
    if (!r.started)
      throw Error(info.path, r.start_errno == ENOENT
                                 ? "colmap binary '" + binary + "' not found"
                                 : "cannot start colmap binary '" + binary + "': " + std::strerror(r.start_errno));
    if (r.term_signal != 0)
      throw Error(info.path, "colmap " + step + " killed by signal " + std::to_string(r.term_signal) + ": " +
                                 LastNonEmptyLine(log));
    if (r.exit_code != 0) throw Error(info.path, "colmap " + step + " failed: " + LastNonEmptyLine(log));
  }
};

// Frames to disk (working resolution) as frame_NNNNNN.jpg; returns each
// frame index's time, increasing (an index the decoder skipped takes its
// neighbour's, nudged).
std::vector<double> ExportFrames(FrameSource& source, const fs::path& images, const ProgressFn& progress) {
  const VideoInfo& info = source.info();
  std::vector<double> times;
  Frame frame;
  long done = 0;
  while (source.Next(&frame)) {
    if (StopRequested()) throw Interrupted(info, "frame export");
    const cv::Mat& img = frame.bgr.empty() ? frame.gray : frame.bgr;
    char name[64];
    std::snprintf(name, sizeof(name), "frame_%06d.jpg", frame.index);
    if (!cv::imwrite((images / name).string(), img, {cv::IMWRITE_JPEG_QUALITY, 95}))
      throw Error((images / name).string(), "cannot write frame");
    if (frame.index >= static_cast<int>(times.size())) times.resize(frame.index + 1, frame.time_s);
    times[frame.index] = frame.time_s;
    ++done;
    if (progress) progress(done, info.frame_count);
  }
  if (times.empty()) throw Error(info.path, "no frames could be decoded");
  for (size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1])) times[i] = times[i - 1] + 1e-6;
  return times;
}

// The mapper's models as text, in `tmp`; the one with the most registered
// images (empty: none).
fs::path LargestModel(const ColmapRunner& colmap, const fs::path& sparse, const fs::path& tmp) {
  fs::path best;
  size_t best_count = 0;
  for (const auto& entry : fs::directory_iterator(sparse)) {
    if (!entry.is_directory()) continue;
    const fs::path txt = tmp / ("txt_" + entry.path().filename().string());
    fs::create_directories(txt);
    colmap.Run("model_converter",
               {"--input_path", entry.path().string(), "--output_path", txt.string(), "--output_type", "TXT"});
    std::ifstream in(txt / "images.txt");
    std::string line;
    size_t count = 0;
    while (std::getline(in, line))
      if (!line.empty() && line[0] != '#') ++count;
    if (count > best_count) {
      best_count = count;
      best = txt;
    }
  }
  return best;
}

}  // namespace

CameraPath EstimateWithColmap(FrameSource& source, const std::string& colmap_binary,
                              const ProgressFn& progress) {
  const VideoInfo& info = source.info();
  ScopedStopSignals stop_signals;  // restored on every exit path
  TempDir tmp;
  const fs::path images = tmp.path / "images", sparse = tmp.path / "sparse";
  fs::create_directories(images);
  fs::create_directories(sparse);
  const ColmapRunner colmap{info, colmap_binary, (tmp.path / "colmap.log").string()};
  const std::vector<double> times = ExportFrames(source, images, progress);
  const std::string db = (tmp.path / "database.db").string();
  colmap.Run("feature_extractor", {"--database_path", db, "--image_path", images.string(),
                                   "--ImageReader.single_camera", "0", "--ImageReader.camera_model",
                                   "SIMPLE_PINHOLE", "--SiftExtraction.use_gpu", "0"});
  colmap.Run("sequential_matcher", {"--database_path", db, "--SiftMatching.use_gpu", "0"});
  colmap.Run("mapper",
             {"--database_path", db, "--image_path", images.string(), "--output_path", sparse.string()});
  const fs::path best = LargestModel(colmap, sparse, tmp.path);
  if (best.empty())
    throw Error(info.path,
                "colmap mapper could not initialise a model (pure rotation, static camera or "
                "too little texture?)");
  ColmapReadOptions ro;
  ro.frame_times = times;
  ro.decoded_width = info.width;
  return ReadColmapTextModel(best.string(), ro);
}

}  // namespace hapcine
