// OpenFrameSource: picks the reader for a path and checks the cheap things
// (exists, non-empty) before any library gets to produce a vaguer message.

#include "extract/frame_source.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "core/input_file.h"
#include "extract/video_sources.h"

namespace hapcine {

void FrameSourceOptions::Check() const {
  if (max_working_side < 0 || max_working_side > 16384)
    throw UsageError("max_working_side must be in [0, 16384] (0 keeps the size)");
  if (max_working_side > 0 && max_working_side < 16)
    throw UsageError("max_working_side must be 0 or at least 16 pixels");
  if (color_max_side < 0) throw UsageError("color_max_side must be >= 0 (0 = working size)");
  if (decode_threads < 0 || decode_threads > 256)
    throw UsageError("decode_threads must be in [0, 256] (0 = automatic)");
  if (!(image_sequence_fps > 0) || !std::isfinite(image_sequence_fps))
    throw UsageError("image_sequence_fps must be a positive number");
}

cv::Size WorkingSize(int decoded_width, int decoded_height, int max_working_side) {
  const int longest = std::max(decoded_width, decoded_height);
  if (max_working_side <= 0 || longest <= max_working_side) {
    return {decoded_width, decoded_height};
  }
  const double s = static_cast<double>(max_working_side) / longest;
  const int w = std::max(1, static_cast<int>(std::lround(decoded_width * s)));
  const int h = std::max(1, static_cast<int>(std::lround(decoded_height * s)));
  return {w, h};
}

std::unique_ptr<FrameSource> OpenFrameSource(const std::string& path,
                                             const FrameSourceOptions& options) {
  options.Check();
  if (path.empty()) throw Error(path, "empty input path");
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  // An existing file named "50%.mp4" is a video, not a pattern.
  const bool is_file = !ec && std::filesystem::is_regular_file(status);
  if (!is_file && IsImageSequencePath(path)) return OpenImageSequence(path, options);
  CheckRegularFile(path);  // "no such file", "not a regular file" (a FIFO, a device)
  // Before FFmpeg, which would call it "not a media file ... (Permission denied)".
  if (::access(path.c_str(), R_OK) != 0)
    throw Error(path, std::string("cannot read the file (") + std::strerror(errno) + ")");
  if (std::filesystem::file_size(path, ec) == 0 && !ec) throw Error(path, "empty file (0 bytes)");
  return OpenFfmpegSource(path, options);
}

}  // namespace hapcine
