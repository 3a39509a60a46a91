#pragma once
// Decoding for the OpenCV peers: cv::VideoCapture (FFmpeg backend), each
// frame shrunk so its longest side is at most `max_side` (0 = as decoded),
// with its presentation time. Timestamps that do not increase are replaced by
// index / fps, so the written path is always valid.

#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace hapcine::bench {

struct VideoInfo {
  int width = 0, height = 0;  // decoded size
  double fps = 0;
  int frames = 0;             // frames actually decoded
};

// Calls `on_frame(index, time_s, working_bgr)` for every frame; returns the
// info. Throws hapcine::Error naming the file when it cannot be opened or
// holds no frame.
VideoInfo ForEachFrame(const std::string& path, int max_side,
                       const std::function<void(int, double, const cv::Mat&)>& on_frame);

// Minimal "--key value" parsing for the peer programs.
std::string ArgValue(int argc, char** argv, const std::string& key, const std::string& fallback);

}  // namespace hapcine::bench
