#pragma once
// Frames in: decoded video (FFmpeg) or an image sequence, delivered one at a
// time at a working resolution, with the container's presentation times.
// Everything streams: nothing here keeps more than a few frames.

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace hapcine {

struct VideoInfo {
  std::string path;
  // Display frame size in square pixels, after rotation metadata: the
  // decoded width times the sample aspect ratio (rounded; anamorphic video
  // is resampled to it), so tracks, focal lengths and FOVs are isotropic.
  int width = 0;
  int height = 0;
  // Sample (pixel) aspect ratio of the decoded picture, width : height of
  // one stored pixel (16:15 for 720x576 PAL 4:3). 1:1 for square pixels and
  // for streams that declare none.
  int sample_aspect_num = 1;
  int sample_aspect_den = 1;
  double fps = 0;         // nominal (average) rate; times come from timestamps
  double duration_s = 0;  // 0 when unknown
  long frame_count = 0;   // estimate; 0 when unknown
  std::string codec;      // e.g. "h264"
  // Display-matrix rotation that was applied to the decoded image, degrees
  // CLOCKWISE (0/90/180/270), exactly as the ffmpeg CLI's autorotate does.
  // Note ffprobe prints the matrix angle counter-clockwise: "rotation=90"
  // (phone held one way, or `-metadata:s:v rotate=90`) is 270 here.
  int rotation_deg = 0;
  // Still images (a folder or pattern): consecutive frames need not be close
  // in time or viewpoint, so the tracker links them by descriptors.
  bool stills = false;
  // Image sequences: the number in each image's file name, by frame index
  // (plate.1001.exr -> 1001); empty when the names carry none, and for video.
  std::vector<int> source_frames;
};

struct Frame {
  int index = 0;       // 0-based decoded frame index
  double time_s = 0;   // presentation time from the container, seconds
  cv::Mat gray;        // CV_8UC1 at working resolution
  cv::Mat bgr;         // CV_8UC3 at working resolution, or smaller (color_max_side); may be empty
  double scale = 1.0;  // working size / decoded size (same for x and y)
  // Decoded frame size (after rotation), in square pixels: for anamorphic
  // video the stored width times the sample aspect ratio, rounded
  // (VideoInfo::width). The working size is rounded to whole
  // pixels, so the exact per-axis scales are gray.cols / decoded_width and
  // gray.rows / decoded_height; `scale` is the one along the longest side.
  // Working -> decoded pixel (OpenCV centre convention, see tracks.h):
  //   p_decoded = (p_working + 0.5) / scale_axis - 0.5
  int decoded_width = 0;
  int decoded_height = 0;
  // With FrameSourceOptions::skip_nonref_frames: the presentation times of
  // the frames the decoder skipped just before this one, in order (their
  // indices are index - size() .. index - 1). Empty otherwise.
  std::vector<double> skipped_before_s;
};

struct FrameSourceOptions {
  // Longest side of the working images, pixels; 0 keeps the decoded size.
  int max_working_side = 960;
  bool want_color = true;  // fill Frame::bgr
  // Longest side of Frame::bgr, pixels; 0 = the working size. Shot detection
  // only needs colour statistics, so the estimator asks for a thumbnail
  // (scaling straight from the decoded frame costs a fraction of a
  // working-size BGR image).
  int color_max_side = 0;
  // Skip H.264/HEVC's in-loop deblocking filter (AVDISCARD_ALL): decoding
  // gets cheaper, the picture gets slightly blockier, and drifts from the
  // encoder's references until the next keyframe. For analysis only.
  bool skip_loop_filter = false;
  // Decode only the frames other frames are predicted from (FFmpeg's
  // skip_frame = AVDISCARD_NONREF): about half the frames of H.264/HEVC with
  // B-frames are never decoded. Frame::index still counts every frame in
  // presentation order (from the packets' timestamps) and
  // Frame::skipped_before_s lists the skipped ones' times. For speed only.
  bool skip_nonref_frames = false;
  int decode_threads = 0;  // 0 = FFmpeg's choice (all cores)
  // Image sequences carry no timestamps: frame i is at time i / this rate.
  double image_sequence_fps = 24;
  void Check() const;  // throws UsageError
};

// The seam that lets tests feed frames without files.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const VideoInfo& info() const = 0;
  // Next frame in presentation order; false at the end. Throws hapcine::Error
  // naming the file on a decode failure that cannot be skipped.
  virtual bool Next(Frame* frame) = 0;
  // With FrameSourceOptions::skip_nonref_frames, once Next() returned false:
  // the presentation times of frames skipped after the last decoded one
  // (indices last index + 1, + 2, ...). Empty otherwise.
  virtual std::vector<double> SkippedAtEnd() const { return {}; }
  // Once Next() returned false: what the caller should tell the user (frames
  // the container declares that could not be decoded, too few to fail on).
  // The source prints nothing itself.
  virtual std::vector<std::string> Warnings() const { return {}; }
};

// Opens a video file (anything FFmpeg reads), an image folder, or a printf
// pattern ("frames/%05d.png"). Throws hapcine::Error("<path>", reason) for
// missing, zero-byte, unreadable, audio-only or undecodable inputs.
std::unique_ptr<FrameSource> OpenFrameSource(const std::string& path,
                                             const FrameSourceOptions& options = {});

}  // namespace hapcine
