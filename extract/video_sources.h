#pragma once
// The concrete FrameSources behind OpenFrameSource(). Internal to extract/:
// callers outside this folder use OpenFrameSource() only.

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "extract/frame_source.h"

namespace hapcine {

// Working image size for a decoded size: longest side <= max_working_side
// (0 = keep), never upscaled, each side rounded to whole pixels and >= 1.
cv::Size WorkingSize(int decoded_width, int decoded_height, int max_working_side);

// Largest frame side accepted; anything bigger is treated as a corrupt header.
constexpr int kMaxFrameSidePx = 16384;

// FFmpeg (libavformat + libavcodec + libswscale) video file reader.
std::unique_ptr<FrameSource> OpenFfmpegSource(const std::string& path,
                                              const FrameSourceOptions& options);

// True if `path` is a folder or contains a printf conversion ("%05d").
bool IsImageSequencePath(const std::string& path);

// Sorted image files of a folder, or a printf pattern; OpenCV imread.
std::unique_ptr<FrameSource> OpenImageSequence(const std::string& path,
                                               const FrameSourceOptions& options);

}  // namespace hapcine
