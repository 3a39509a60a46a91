#pragma once
// Frames in: decoded video (FFmpeg) or an image sequence, delivered one at a
// time at a working resolution, with the container's presentation times.
// Everything streams: nothing here keeps more than a few frames.

#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace hapcine {

struct VideoInfo {
  std::string path;
  int width = 0;           // decoded frame size, after rotation metadata
  int height = 0;
  double fps = 0;          // nominal (average) rate; times come from timestamps
  double duration_s = 0;   // 0 when unknown
  long frame_count = 0;    // estimate; 0 when unknown
  std::string codec;       // e.g. "h264"
  int rotation_deg = 0;    // display-matrix rotation that was applied (0/90/180/270)
};

struct Frame {
  int index = 0;           // 0-based decoded frame index
  double time_s = 0;       // presentation time from the container, seconds
  cv::Mat gray;            // CV_8UC1 at working resolution
  cv::Mat bgr;             // CV_8UC3 at working resolution (for shot detection/preview); may be empty
  double scale = 1.0;      // working size / decoded size (same for x and y)
};

struct FrameSourceOptions {
  // Longest side of the working images, pixels; 0 keeps the decoded size.
  int max_working_side = 960;
  bool want_color = true;  // fill Frame::bgr
  int decode_threads = 0;  // 0 = FFmpeg's choice (all cores)
  void Check() const;      // throws UsageError
};

// The seam that lets tests feed frames without files.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const VideoInfo& info() const = 0;
  // Next frame in presentation order; false at the end. Throws hapcine::Error
  // naming the file on a decode failure that cannot be skipped.
  virtual bool Next(Frame* frame) = 0;
};

// Opens a video file (anything FFmpeg reads), an image folder, or a printf
// pattern ("frames/%05d.png"). Throws hapcine::Error("<path>", reason) for
// missing, zero-byte, unreadable, audio-only or undecodable inputs.
std::unique_ptr<FrameSource> OpenFrameSource(const std::string& path,
                                             const FrameSourceOptions& options = {});

}  // namespace hapcine
