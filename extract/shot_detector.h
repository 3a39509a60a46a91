#pragma once
// Shot boundaries from colour statistics, one frame at a time (causal).
//
//  - Blank frames: mean luma < blank_luma or luma std-dev < blank_stddev
//    (black, white flash, flat grey), measured on a 128-px-wide point-sampled thumbnail.
//  - Hard cut: the Bhattacharyya distance between consecutive HSV histograms
//    (16 hue x 4 saturation x 8 value bins; a 64-bin luma histogram when the
//    frame has no colour) exceeds an adaptive threshold
//        T_cut = max(cut_threshold, mean + 6 std)
//    over the last 30 distances of the shot, so busy footage raises it.
//  - Gradual transitions, twin comparison (Zhang, Kankanhalli & Smoliar 1993):
//    a run of frames whose distance exceeds
//        T_low = max(0.1 cut_threshold, mean + 3 std)
//    is a candidate; if, when the run ends, the frame before the run and the
//    frame after it differ by more than cut_threshold, a kFade boundary is
//    reported on the first frame after the run. Frames in a run are flagged
//    `transition`. A run needs 3 calm frames of the shot before it (so a
//    fade-in right after black is not a second boundary) and is abandoned
//    after 90 frames (slow drift, not a transition).
//  - Fades through black: blank frames belong to the current shot; the first
//    non-blank frame after them starts a new shot (kFade) if the shot had
//    content before the black. That first frame is flagged `transition` (it
//    is usually the start of a fade-in).
//  - Spikes, for cuts between look-alike shots (two views of the same set
//    have close histograms, under T_cut): `spike` is set when the distance
//    is at least twice the median of the shot's last 5 distances (transition
//    frames included, so a pan's steady change raises the bar) and above
//    mean + 6 std of its calm distances. A spike alone is not a cut (the
//    first frame of every camera move is one); FeatureTracker makes it one
//    when tracking collapses on the same frame, the descriptors do not
//    re-link and the picture is not continuous with the last one (below),
//    and then calls MarkCut().
//  - Continuity: the largest normalised cross-correlation between the
//    middle of the previous frame and the current frame, on 64-px blurred
//    gray thumbnails, over shifts up to a fifth of each side. At that scale
//    motion blur and a fast handheld move leave the picture's layout (one
//    frame is the last one shifted), while a cut brings an unrelated one.

#include <deque>
#include <opencv2/core.hpp>

#include "extract/frame_source.h"
#include "extract/tracks.h"

namespace hapcine {

// Width of the thumbnail the statistics are measured on; a Frame::bgr this
// small is used as it is.
constexpr int kShotThumbWidth = 128;

struct ShotDetectorOptions {
  double cut_threshold = 0.5;  // Bhattacharyya distance floor for a hard cut
  double blank_luma = 16;      // mean luma (0..255) under which a frame is blank
  double blank_stddev = 4;     // luma std-dev under which a frame is blank
};

struct ShotDecision {
  ShotBoundary boundary = ShotBoundary::kNone;  // kCut / kFade start a new shot here
  bool blank = false;
  bool transition = false;  // inside a candidate gradual transition
  double distance = 0;      // histogram distance to the previous frame
  double mean_luma = 0;
  double luma_stddev = 0;
  bool spike = false;       // distance far above the shot's recent ones (see above)
  // Best NCC of the last frame's middle in this one (see above); 1 when
  // there is no last frame (first, after blank).
  double continuity = 1;
  // A candidate gradual transition ended on this frame without a boundary:
  // the frames before and after it have close histograms (two views of one
  // set dissolve into each other so). FeatureTracker compares the pictures
  // with the tracked motion taken out (MovedPictureChange).
  bool look_alike_run_ended = false;
};

// Pictures "continue" (one is the other moved) above this continuity: a
// fast handheld move with motion blur keeps >= 0.92 between consecutive
// frames at 64 px, a cut between unrelated pictures of similar colours
// reaches 0.58-0.61 (docs/extract.md); the maximum over a few hundred
// shifts of an unrelated picture is what the margin guards against.
constexpr double kContinuousPicture = 0.8;

// How much of the picture is another picture after the motion is taken
// out: `before` moved by `now_from_before` (a homography in pixels of
// images of `working` size) against `now`, both layout thumbnails
// (ShotDetector::layout()), compared cell by cell on a 4 x 3 grid; the share
// of the compared cells (covered and textured) whose NCC is under
// kContinuousPicture. A dissolve changes the whole picture (share near 1),
// a pan none of it, a person moving in front of the camera a compact part.
// NaN when under a third of the cells can be compared.
constexpr int kChangeGridCols = 4, kChangeGridRows = 3;
// Width of the layout thumbnails the picture is compared on (continuity,
// MovedPictureChange), pixels.
constexpr int kLayoutWidth = 64;
double MovedPictureChange(const cv::Mat& before, const cv::Mat& now,
                          const cv::Matx33d& now_from_before, cv::Size working);

class ShotDetector {
 public:
  explicit ShotDetector(const ShotDetectorOptions& options = {}) : options_(options) {}
  // Frames in order. The first frame never reports a boundary (the caller
  // marks it kStart).
  ShotDecision Update(const Frame& frame);
  // The caller found a cut on the frame last passed to Update(): start the
  // shot's statistics over from that frame.
  void MarkCut() { StartShot(); }
  // The layout thumbnail (Continuity) of the frame last passed to Update();
  // empty for a blank frame.
  const cv::Mat& layout() const { return layout_; }

 private:
  void StartShot();
  bool IsSpike(double d, double calm_limit) const;
  // The layout thumbnail of this frame; returns its continuity with the last.
  double UpdateLayout(const cv::Mat& gray_thumb);
  // Mean and std-dev of the shot's calm distances (0 without any).
  void RecentStatistics(double* mean, double* stddev) const;

  ShotDetectorOptions options_;
  cv::Mat prev_hist_;              // last non-blank frame's histogram
  cv::Mat prev_layout_;            // last non-blank frame's blurred 64-px gray thumbnail
  cv::Mat layout_;                 // the last frame's (empty: blank)
  std::deque<double> recent_;      // calm distances of the current shot
  std::deque<double> local_;       // last distances of the shot, calm or not
  bool shot_has_content_ = false;  // a non-blank frame was seen in this shot
  bool in_blank_run_ = false;
  int calm_frames_ = 0;  // non-transition frames in this shot
  bool candidate_ = false;
  bool candidate_allowed_boundary_ = false;
  int candidate_len_ = 0;
  cv::Mat candidate_start_hist_;
};

}  // namespace hapcine
