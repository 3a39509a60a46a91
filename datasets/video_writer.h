#pragma once
// H.264 MP4 writer on libavformat/libavcodec (encoder "libx264", yuv420p).
//
// Frame k gets pts = k in a time base of 1/fps (fps as an exact rational for
// common rates such as 24000/1001), so a decoder sees
// time_s = k / fps -- the ground-truth CSV uses the same formula. Colour is
// converted with swscale's BT.601 limited-range matrix and the stream is
// tagged as such (smpte170m), so decoders invert exactly that matrix.
//
// The file is written under a temporary name (TempOutput, core/output_files.h)
// and renamed onto the final path only by Close(); a writer destroyed without
// Close(), or a failing Close(), leaves nothing behind. Errors throw hapcine::Error naming
// the file.

#include <opencv2/core.hpp>
#include <string>

#include "core/output_files.h"

struct AVFormatContext;
struct AVCodecContext;
struct AVStream;
struct AVFrame;
struct AVPacket;
struct SwsContext;

namespace hapcine {

struct VideoWriterOptions {
  int crf = 18;                  // x264 constant rate factor (0 = lossless .. 51 = worst)
  std::string preset = "fast";   // x264 speed preset (ultrafast .. veryslow)
  int gop = 48;                  // max frames between keyframes
  int threads = 0;               // encoder threads (0 = x264's automatic choice)
  // false: write `path` itself, for a caller whose own temporary it is (the
  // preview muxes the film's audio in afterwards).
  bool atomic = true;
};

class VideoWriter {
 public:
  VideoWriter() = default;
  ~VideoWriter();  // aborts an unclosed file: removes the temporary
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // width and height must be even (yuv420p); fps > 0.
  void Open(const std::string& path, int width, int height, double fps,
            const VideoWriterOptions& options = {});
  // One BGR frame, CV_8UC3, exactly width x height.
  void Write(const cv::Mat& bgr);
  // Flushes the encoder, writes the trailer and renames onto the final path.
  void Close();

  bool is_open() const { return format_ != nullptr; }
  int frames_written() const { return frames_; }

 private:
  void Encode(AVFrame* frame);  // nullptr flushes
  void Abort() noexcept;

  std::string path_;
  TempOutput output_;
  int width_ = 0, height_ = 0, frames_ = 0;
  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVStream* stream_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* sws_ = nullptr;
  bool header_written_ = false;
};

}  // namespace hapcine
