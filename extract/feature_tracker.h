#pragma once
// Shot detection + feature tracking over a FrameSource, one frame at a time.
//   pyramidal KLT with a forward-backward check (started from each track's
//   last motion when the picture moves fast), detections spread over a
//   grid and topped up as tracks die, descriptor (ORB) matching to re-link
//   when tracking collapses (whip pans, blur), SIFT linking where KLT cannot
//   bridge (stills, jumps, fast orbits); hard cuts and fades split shots;
//   blank frames are flagged and not tracked.

#include <memory>

#include "extract/frame_source.h"
#include "extract/tracks.h"

namespace hapcine {

struct TrackerOptions {
  int max_tracks = 600;            // wanted live tracks per frame
  int grid_cols = 8, grid_rows = 6;  // detections spread over this grid
  double min_distance_px = 8;      // between detections, working pixels
  // KLT window side, working pixels. 17, not 21: OpenCV's LK works in
  // 8-pixel SIMD strips, so 17 = 16 + a 1-pixel scalar tail where 21 has a
  // 5-pixel one (and 15 a 7-pixel one): 17 costs ~40 % less KLT CPU than 21
  // and less than 15 (docs/extract.md "Speed").
  int klt_window = 17;
  int pyramid_levels = 4;
  double fb_threshold_px = 0.5;    // forward-backward error limit, working pixels
  // KLT stops at 30 iterations or a step below 0.01 px at the finest level;
  // on the coarser levels (which only seed the next one) at these.
  int klt_coarse_iterations = 10;
  double klt_coarse_step_px = 0.1;
  // Start each track's KLT where its last displacement takes it (constant
  // velocity; the median displacement for new tracks) instead of at zero
  // motion: fast pans stay within the pyramid's reach.
  bool klt_predict = true;
  // In a fade, track each frame at the last tracked picture's mean and
  // contrast (IsFadeStep, ContrastMatched). Off by default: with the test
  // look's lens distortion it moves that fade's focal the wrong way (docs/extract.md).
  bool match_fade_contrast = false;
  // Vignetting: estimate the lens's fixed radial darkening from the tracks'
  // brightness as they move across the picture (VignettingFit) and, once
  // the data demand a field, track on frames divided by it (flat field):
  // the fall-off's slope does not move with the texture and LK reads the
  // edges' motion short. Footage without vignetting is tracked as before.
  // Off by default: on the test look it helps whip pans but not every
  // clip (docs/extract.md "Vignetting").
  bool flat_field_vignetting = false;
  // KLT drift bound: frame-to-frame KLT adds a small error every frame, so
  // a track's error grows with its age. Every track is also tracked from
  // the frame where it was detected (its anchor), at the finest pyramid
  // level, starting at its frame-to-frame position, and takes that answer;
  // a track whose correction is an outlier among this frame's (median +
  // 3 robust sigmas, at least klt_anchor_min_px) slipped and is dropped.
  // The anchor moves to the current frame after klt_anchor_frames frames
  // (the patch's appearance changes as the view turns). 0: off.
  int klt_anchor_frames = 0;
  double klt_anchor_min_px = 0.5;
  // The anchor check aligns the anchor's patch by an affine warp (and gain,
  // bias) instead of a translation: it follows the patch's change of shape.
  bool klt_anchor_affine = false;
  bool descriptor_recovery = true; // ORB re-linking when tracking collapses
  // SIFT linking where KLT cannot bridge (descriptor_linker.h): tried when
  // fewer than 70 % of the tracks survive KLT, taken when KLT's survivors
  // disagree with the verified two-view geometry; the following frames are
  // then linked by descriptors until the motion is back within KLT's reach.
  bool descriptor_linking = true;
  // Every frame is a still (image folders and patterns; `--stills`): frames
  // are linked by descriptors from the first (KLT takes over where a link
  // measures a motion within its reach), and only a failed link (to the last
  // frame or the last well-linked one), not the histogram, splits a shot.
  bool stills = false;
  // A video whose shot jumps beyond KLT's reach from its very first step
  // (the descriptors verify a motion of a KLT window or more where KLT lost
  // most tracks) is a sequence of stills too, until a link measures a
  // motion within KLT's reach.
  bool stills_by_evidence = true;
  // Revisit links: a video shot's views where half the last one's tracks
  // ended are kept (pictures and tracks); at each new one, the earlier views
  // that share no live track but look like it (layout thumbnail) are linked
  // by descriptors, and their tracks continued here: an orbit that comes
  // round again observes the points it triangulated a turn before, which
  // KLT tracks (which die within a part of the turn) cannot. Off by default.
  bool revisit_links = false;
  // A break inside a video shot (KLT, the ORB re-links and the SIFT probe
  // all lost the last frame, and no cut was seen: blur, a flash, an
  // occluder): the next frames, for up to half a second, are linked by SIFT to
  // the last frame before the break; the first that links continues its
  // tracks, so the shot goes on (FrameTracks::bridging).
  bool bridge_breaks = true;
  // Shot detection
  double cut_threshold = 0.5;      // histogram distance for a hard cut
  double blank_luma = 16;          // mean luma (0..255) under which a frame is blank
  double blank_stddev = 4;         // or whose contrast is below this
  void Check() const;              // throws UsageError
};

// Lucas-Kanade assumes a point keeps its brightness; in a fade the whole
// picture is scaled from frame to frame and KLT reads too little motion.
// IsFadeStep: the reference's mean and contrast (standard deviation) over a
// frame's are one factor (within kFadeFactorAgreement of its log) and differ
// from 1 by more than kContrastChangeToMatch. ContrastMatched: `gray` (whose
// mean and standard deviation are `mean`, `stddev`) with its mean and
// contrast set to the reference's on such a step; otherwise `gray` itself
// (shared), so ordinary footage is tracked as before.
// `*gain`: the contrast factor applied (1: none).
constexpr double kContrastChangeToMatch = 0.02;
constexpr double kFadeFactorAgreement = 0.5;
bool IsFadeStep(double mean_ratio, double contrast_ratio);
cv::Mat ContrastMatched(const cv::Mat& gray, double mean, double stddev, double reference_mean,
                        double reference_stddev, double* gain);

class Diagnostics;

class FeatureTracker {
 public:
  // `diagnostics`: where the look-alike cut test's cues go, one "cut_cues"
  // record per tracked frame when wanted (core/diagnostics.h); not owned.
  explicit FeatureTracker(const TrackerOptions& options = {}, Diagnostics* diagnostics = nullptr);
  ~FeatureTracker();
  // Processes the next frame (frames must come in order) and returns its tracks.
  FrameTracks Process(const Frame& frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hapcine
