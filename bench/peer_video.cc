#include "bench/peer_video.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/error.h"

namespace hapcine::bench {

VideoInfo ForEachFrame(const std::string& path, int max_side,
                       const std::function<void(int, double, const cv::Mat&)>& on_frame) {
  cv::VideoCapture cap(path, cv::CAP_FFMPEG);
  if (!cap.isOpened()) throw Error(path, "cannot open video");
  VideoInfo info;
  info.fps = cap.get(cv::CAP_PROP_FPS);
  if (!(info.fps > 0 && info.fps < 1000)) info.fps = 25;
  cv::Mat frame, work;
  double last_t = -1;
  while (cap.read(frame)) {
    if (frame.empty()) break;
    info.width = frame.cols;
    info.height = frame.rows;
    double t = cap.get(cv::CAP_PROP_POS_MSEC) / 1000.0;
    if (!std::isfinite(t) || t <= last_t) t = info.frames / info.fps;
    if (t <= last_t) t = last_t + 1e-6;
    last_t = t;
    const int side = std::max(frame.cols, frame.rows);
    if (max_side > 0 && side > max_side) {
      const double s = static_cast<double>(max_side) / side;
      cv::resize(frame, work, cv::Size(), s, s, cv::INTER_AREA);
    } else {
      work = frame;
    }
    on_frame(info.frames, t, work);
    ++info.frames;
  }
  if (info.frames == 0) throw Error(path, "no frame could be decoded");
  return info;
}

std::string ArgValue(int argc, char** argv, const std::string& key, const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (key == argv[i]) return argv[i + 1];
  return fallback;
}

}  // namespace hapcine::bench
