// FeatureTracker: shot detection, then pyramidal KLT with a forward-backward
// check between consecutive working images, grid top-up detections, and ORB
// re-linking when tracking collapses. See feature_tracker.h / docs/extract.md.
//
// Per frame cost: one pyramid (with derivatives) built once and used three
// times (backward check now, forward flow next frame); two LK passes over the
// live tracks (two more, from zero motion, over the tracks a predicted start
// lost on a fast pan); corner detection only when the track count fell
// below 90% of max_tracks; ORB only on collapse.

#include "extract/feature_tracker.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "core/diagnostics.h"
#include "core/error.h"
#include "core/statistics.h"
#include "extract/affine_lk.h"
#include "extract/descriptor_linker.h"
#include "extract/descriptor_relinker.h"
#include "extract/grid_detector.h"
#include "extract/keep_tracks.h"
#include "extract/pyramid_lk.h"
#include "extract/shot_detector.h"
#include "extract/vignetting.h"

namespace hapcine {

void TrackerOptions::Check() const {
  if (max_tracks < 10) throw UsageError("max_tracks must be at least 10");
  if (grid_cols < 1 || grid_rows < 1 || grid_cols > 64 || grid_rows > 64)
    throw UsageError("grid_cols and grid_rows must be in 1..64");
  if (!(min_distance_px >= 1)) throw UsageError("min_distance_px must be >= 1");
  if (klt_window < 5 || klt_window > 101 || klt_window % 2 == 0)
    throw UsageError("klt_window must be odd, 5..101");
  if (pyramid_levels < 1 || pyramid_levels > 8) throw UsageError("pyramid_levels must be 1..8");
  if (!(fb_threshold_px > 0)) throw UsageError("fb_threshold_px must be > 0");
  if (klt_anchor_frames < 0 || klt_anchor_frames > 10000)
    throw UsageError("klt_anchor_frames must be 0..10000");
  if (!(klt_anchor_min_px > 0)) throw UsageError("klt_anchor_min_px must be > 0");
  if (klt_coarse_iterations < 1 || klt_coarse_iterations > 100)
    throw UsageError("klt_coarse_iterations must be 1..100");
  if (!(klt_coarse_step_px > 0 && klt_coarse_step_px <= 1))
    throw UsageError("klt_coarse_step_px must be in (0, 1]");
  if (!(cut_threshold > 0 && cut_threshold <= 1))
    throw UsageError("cut_threshold must be in (0, 1]");
  if (!(blank_luma >= 0 && blank_luma < 255)) throw UsageError("blank_luma must be in [0, 255)");
  if (!(blank_stddev >= 0)) throw UsageError("blank_stddev must be >= 0");
}

bool IsFadeStep(double mean_ratio, double contrast_ratio) {
  // Grain and compression move a frame's contrast by well under 2 %; a fade
  // moves it by more (a 1 s fade: ~4 % a frame).
  if (std::abs(contrast_ratio - 1) <= kContrastChangeToMatch || std::abs(mean_ratio - 1) <= kContrastChangeToMatch)
    return false;
  // A fade scales the picture, its mean and its contrast by one factor;
  // motion blur lowers the contrast alone, new content moves either.
  const double log_contrast = std::log(contrast_ratio), log_mean = std::log(mean_ratio);
  return log_contrast * log_mean > 0 && std::abs(log_mean - log_contrast) < kFadeFactorAgreement * std::abs(log_contrast);
}

cv::Mat ContrastMatched(const cv::Mat& gray, double mean, double stddev, double reference_mean,
                        double reference_stddev, double* gain) {
  *gain = 1;
  // A blank (or flat) frame has no contrast to match; nor has a blank reference.
  if (!(stddev > 1 && reference_stddev > 1 && mean > 1 && reference_mean > 1)) return gray;
  const double a = reference_stddev / stddev;
  if (!IsFadeStep(reference_mean / mean, a)) return gray;
  cv::Mat matched;
  gray.convertTo(matched, -1, a, reference_mean - a * mean);
  *gain = a;
  return matched;
}

namespace {

// An unknown displacement (a new track's, no tracks' at all).
constexpr float kNoMotion = std::numeric_limits<float>::quiet_NaN();
// A collapse: fewer than this fraction of last frame's tracks survived.
constexpr double kCollapseFraction = 0.3;
// Below this many live tracks there is nothing to "collapse" from.
constexpr size_t kMinTracksForCollapse = 20;
// A frame is a good keyframe for recovery when this fraction survived.
constexpr double kGoodSurvival = 0.7;
// Quality cap for frames inside a suspected fade/dissolve.
constexpr double kTransitionQualityCap = 0.25;
// A gradual histogram change that KLT followed from frame to frame, with at
// least this share of the tracks surviving each frame and the image content
// moving by at least kMotionRunShare of the working width in all, is the
// camera moving (a pan or tilt brings new colours into view), not a dissolve.
// A dissolve on a still camera keeps tracks alive but does not move them.
// A whip pan blurs the picture: only 20-35 % of the tracks pass the
// forward-backward check each frame (measured on an 80 deg whip), but they
// all agree on a large motion.
constexpr double kMotionRunSurvival = 0.2;
constexpr double kMotionRunShare = 0.05;
// A cut between look-alike shots: at most this share of last frame's tracks
// still verified (after the collapse's consistency check). A cut between
// two views of one set: 0 of 541; a blurred whip pan keeps 22-35 %
// (docs/extract.md).
constexpr double kCutSurvival = 0.1;
// A run of gradual change ends on another picture when at least this share
// of the picture's cells (MovedPictureChange) no longer match the picture
// before it, moved as the tracks moved: a dissolve changes every cell, a
// mover the cells it covers (a head filling half the frame: half of them).
constexpr double kDissolvedShare = 0.75;
// Share of a frame's tracks one homography must explain to a pixel for the
// run's chained motion to predict the picture (ExplainsThePicture).
constexpr double kPictureExplained = 0.8;
// The affine anchor check's residual (RMS over the patch's contrast) below
// which a patch still matches whatever the frame's others do: 8-bit
// rounding, resampling and compression leave a few percent on a clean
// still picture, where the robust bound of near-zero residuals would end
// tracks at random.
constexpr float kAnchorResidualFloor = 0.1f;
// Correspondences a run frame's homography is fitted to (ChainRunMotion).
constexpr size_t kChainPoints = 100;
// The vignetting fit decides again once its pairs grew by this factor: a
// field is found within a frame or two of the evidence, and a video
// without one costs a few fits over all its pairs in all.
constexpr double kVignettingDecisionGrowth = 1.25;
// Reprojection bound of the dominant motion's inliers, working px (as the
// collapse's consistency check).
constexpr double kVignettingInlierPx = 2.0;
// The pyramid level whose picture gives a point's local brightness (smoothed
// over a few pixels: a track's sub-pixel error barely changes it).
constexpr int kBrightnessLevel = 2;
// Earlier stills each still is linked to (LinkEarlierViews): a bound on the
// SIFT matching per still; views further round share nothing anyway.
constexpr size_t kStillsViewsBack = 8;
// Views kept of each finished stills shot (its first and its last ones:
// where a split shot meets the others) and of how many shots, for the links
// across stills splits (LinkEarlierShots): a bound on the matching per still.
constexpr size_t kShotEndViews = 2;
constexpr size_t kEarlierStillsShots = 8;
// Revisit links (revisit_links): the views kept per shot (the oldest is
// dropped beyond) and the earlier views one view is linked to at most, the
// most alike first: a bound on the SIFT matching per view.
constexpr size_t kRevisitViews = 64;
constexpr size_t kRevisitTries = 3;
// A frame becomes a revisit view once under this share of the last view's
// tracks live (a fifth replaced: views a few degrees of an orbit apart, so
// a revisit finds one near its own viewpoint). An earlier view is a revisit
// candidate where at most kRevisitShared of its tracks still live: KLT
// links it to this frame no more.
constexpr double kRevisitViewKept = 0.8;
constexpr double kRevisitShared = 0.1;
// A break inside a take (BridgeBreak): the later frames are linked back to
// the last frame before it for at most this long. Blur, a flash or an
// occluder passing the lens lose a few frames; after half a second the camera
// may be anywhere and a split is the honest answer. The tries bound the
// SIFT cost at high frame rates.
constexpr double kBridgeSeconds = 0.5;
constexpr int kBridgeTries = 15;

}  // namespace

struct FeatureTracker::Impl {
  explicit Impl(const TrackerOptions& o)
      : options(o),
        shots(ShotDetectorOptions{o.cut_threshold, o.blank_luma, o.blank_stddev}),
        linker(LinkerOptions(o)),
        descriptor_mode(o.stills) {}

  TrackerOptions options;
  Diagnostics* diagnostics = nullptr;  // "cut_cues" records
  ShotDetector shots;
  DescriptorRelinker relinker;
  DescriptorLinker linker;
  // Linking every frame by descriptors (stills, or KLT could not bridge).
  bool descriptor_mode = false;
  // A video found to be a sequence of stills (StillsByEvidence): linked as
  // stills until a link measures a motion within KLT's reach.
  bool stills_by_evidence = false;
  int shot_tracked_frames = 0;  // tracked frames of the current shot so far
  DescribedFrame last_described;  // the last frame, in descriptor mode
  DescribedFrame good_described;  // the last well-linked one (or a shot's first)
  LinkResult last_link;           // the last link's motion: the next one's prediction
  std::deque<DescribedFrame> stills_views;  // the shot's last stills, oldest first
  // A stills view as kept for the links across splits: its shot and index.
  struct ShotView {
    DescribedFrame view;
    int shot = 0, index = 0;
  };
  std::deque<ShotView> shot_first_stills, shot_last_stills;  // the current stills shot's ends
  // A finished stills shot's first views and last views (the last first):
  // each end tried from its outermost view inwards.
  struct StillsShotEnds {
    std::vector<ShotView> first, last;
  };
  std::deque<StillsShotEnds> earlier_stills_shots;  // oldest first
  // Video: the shot's frames a jump frame is linked back to (LinkEarlierViews),
  // oldest first: a frame KLT tracked per KLT window of motion (described
  // only when a jump needs it) and the jump frames themselves.
  std::deque<DescribedFrame> shot_views;
  // Revisit links: the shot's revisit views, oldest first, each with its
  // layout thumbnail (RevisitStep).
  struct RevisitView {
    DescribedFrame view;  // picture (copied), track points and ids; described when first linked
    cv::Mat layout;
  };
  std::deque<RevisitView> revisit_views;
  // A break inside the shot (BridgeBreak): the last frame before it (picture
  // copied, its tracks; described at the first try) while the later frames
  // are linked back to it, when the break began and the tries so far.
  DescribedFrame break_anchor;
  double break_time_s = 0;
  int break_tries = 0;
  int break_shot = 0;  // the anchor's shot (a cut the bridge withdraws returns to it)
  // This frame: the shot detector's cut, whose picture continues the last
  // (CutMayBeABreak), and whether the bridge began here.
  bool cut_may_be_a_break = false, break_began = false;
  bool first = true;
  int shot = 0;
  long next_id = 0;
  std::vector<cv::Mat> prev_pyramid;
  double last_mean = 0, last_stddev = 0;  // of the picture prev_pyramid was built from
  std::vector<cv::Mat> spare_pyramid;  // buffers reused for the next pyramid
  size_t tracks_after_detect = 0;      // live tracks right after the last top-up
  int frames_since_detect = 0;
  cv::Size prev_size;
  std::vector<cv::Point2f> prev_points;
  std::vector<long> prev_ids;
  // Each previous point's displacement over its last frame (x NaN: none, as
  // for new detections and re-links); seeds the next KLT (klt_predict).
  // Per frame of the video: a decoder that skipped frames (--skip-nonref)
  // leaves index gaps, and a displacement over k frames counts 1/k.
  std::vector<cv::Point2f> prev_velocity;
  int prev_index = -1;  // the last frame's index (blank or not)
  int step = 1;         // this frame's FrameTracks::step, for the prediction
  // Median of prev_velocity, and the same a frame earlier (x NaN: none).
  cv::Point2f motion_last{kNoMotion, kNoMotion}, motion_before{kNoMotion, kNoMotion};
  // The current run of transition-flagged frames, as the tracker saw it.
  bool after_blank = false;    // the previous frame was blank
  RelinkResult bridge;         // re-links across a fade through black
  bool run_tracked = true;    // every frame of the run kept kMotionRunSurvival of its tracks
  double run_motion_px = 0;   // sum over the run of the median track displacement
  // The picture before the run (layout thumbnail) and the homography the
  // tracks followed since (working px; chain false once a frame of the run
  // had no fit): a run that the motion explains shows the same picture moved.
  cv::Mat run_before_layout, last_layout;
  cv::Matx33d run_motion = cv::Matx33d::eye();
  bool run_chain = true;
  // Where the run's tracks were on the frame before it (by id): the chain is
  // checked against them, since per-frame fits hide a slow parallax drift.
  std::unordered_map<long, cv::Point2f> run_start_points;
  // KLT drift bound (klt_anchor_frames): each live track's anchor, and the
  // finest pyramid level {image, derivatives} of every frame still an
  // anchor, by frame index.
  struct TrackAnchor {
    cv::Point2f point;
    int frame = 0;
    cv::Matx22f linear = cv::Matx22f::eye();  // the last affine fit (klt_anchor_affine)
    float residual = 0;                        // its normalised residual
  };
  std::unordered_map<long, TrackAnchor> anchors;
  std::unordered_map<int, std::vector<cv::Mat>> anchor_levels;
  int prev_tracked_index = -1;  // the last tracked frame's index
  // Vignetting (flat_field_vignetting): the fit while no field is found,
  // the field once found (for the rest of the video: one lens), its gain
  // at the working size, and whether prev_pyramid was built flat-fielded.
  // flat_version counts the fields taken (0: none, raw frames); each
  // pyramid remembers the one it was built with.
  VignettingFit vignetting_fit;
  VignettingModel vignetting;
  bool vignetting_decided = false;  // the field will not change any more
  int flat_version = 0, flat_gain_version = 0, prev_flat_version = 0;
  cv::Mat flat_gain;
  cv::Mat last_raw, prev_raw;  // the raw frame of this step and the last (while the field may change)
  size_t next_vignetting_decision = kMinVignettingPairs;  // the fit's pairs at its next decision

  void DropTracks() {
    prev_pyramid.clear();
    prev_points.clear();
    prev_ids.clear();
    prev_velocity.clear();
    motion_last = motion_before = {kNoMotion, kNoMotion};
    relinker.Clear();
    anchors.clear();
    anchor_levels.clear();
    last_described = good_described = {};
    last_link = {};
    stills_views.clear();
    KeepStillsShotEnds();
    shot_views.clear();
    revisit_views.clear();
    break_anchor = {};
    descriptor_mode = Stills();
    shot_tracked_frames = 0;
  }

  // The guided KLT of the descriptor linker: the tracker's window and
  // criteria, the pyramid's coarse levels for the residual of the warp.
  static DescriptorLinkerOptions LinkerOptions(const TrackerOptions& o) {
    DescriptorLinkerOptions l;
    l.max_features = 2 * o.max_tracks;
    l.lk.window = {o.klt_window, o.klt_window};
    l.lk.max_level = o.pyramid_levels - 1;
    l.lk.fine = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
    l.lk.coarse = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, o.klt_coarse_iterations,
                                   o.klt_coarse_step_px);
    l.fb_threshold_px = o.fb_threshold_px;
    return l;
  }

  bool Stills() const { return options.stills || stills_by_evidence; }

  cv::Size Window() const { return {options.klt_window, options.klt_window}; }

  // 30 iterations or a 0.01-px step at level 0; the coarse levels only seed
  // the next finer one (pyramid_lk.h).
  PyramidLkOptions LkOptions() const {
    PyramidLkOptions o;
    o.window = Window();
    o.max_level = options.pyramid_levels - 1;
    o.fine = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
    o.coarse = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                options.klt_coarse_iterations, options.klt_coarse_step_px);
    return o;
  }

  // Adds one transition-flagged frame to the run statistics: `verified`
  // tracks (KLT survivors and descriptor re-links) of `before`, and the
  // displacements of the tracks that moved (KLT: since the last frame;
  // re-links after a collapse: since the relinker's keyframe, as a whip pan
  // outruns KLT). Tracking lost *after* the run has shown camera motion
  // does not undo it: that is a whip pan at its fastest, blurred past what
  // KLT and the descriptors can match (a dissolve keeps its tracks still).
  void AccumulateRun(size_t before, size_t verified, std::vector<float> disp, int working_width) {
    if (before < kMinTracksForCollapse || disp.empty() ||
        verified < kMotionRunSurvival * static_cast<double>(before)) {
      if (run_motion_px < kMotionRunShare * working_width) run_tracked = false;
      return;
    }
    run_motion_px += Quantile(std::move(disp), 0.5);
  }

  bool RunWasCameraMotion(cv::Size working) const {
    return run_tracked && !prev_points.empty() && run_motion_px >= kMotionRunShare * working.width &&
           !(RunPictureChange(working) >= kDissolvedShare);
  }

  // Twin comparison with the motion taken out: the picture before the run,
  // moved as the tracks moved, against the run's last picture. A pan
  // brings new colours into view but what stays in view is the same; a
  // dissolve during a pan is tracked too (KLT follows the fading picture)
  // but ends on another picture, over the whole frame (a person crossing
  // changes a compact part). Without a chain or an overlap to compare: NaN.
  double RunPictureChange(cv::Size working) const {
    if (!run_chain || run_before_layout.empty() || last_layout.empty())
      return std::numeric_limits<double>::quiet_NaN();
    return MovedPictureChange(run_before_layout, last_layout, run_motion, working);
  }

  // A run between look-alike pictures (close histograms before and after)
  // that the tracks followed, ending on another picture: a dissolve between
  // two views of one set. Both cues: appearance (the moved picture) and
  // tracking (the chain that moved it).
  bool IsLookAlikeDissolve(const ShotDecision& decision, cv::Size working) const {
    return decision.look_alike_run_ended && RunPictureChange(working) >= kDissolvedShare;
  }

  // A hard cut the histogram test missed (two views of the same set look
  // alike): all four cues on one frame -- the histogram distance spikes
  // against the shot's recent distances, KLT loses nearly every track,
  // descriptor matching against the last good frame finds no common plane,
  // and the picture does not continue the last one at 64 px (continuity).
  // Each cue alone fires on ordinary footage (a spike at the start of every
  // move, a collapse in a whip pan, no re-link after a long fast pan); the
  // first three together on a fast handheld move blurred past KLT and ORB,
  // which still shows the last picture shifted.
  static bool IsLookAlikeCut(const ShotDecision& decision, bool collapsed, size_t before,
                             size_t survived, const RelinkResult& relink) {
    return decision.spike && collapsed && survived <= kCutSurvival * static_cast<double>(before) &&
           relink.current_from_key.empty() && decision.continuity < kContinuousPicture;
  }

  // Makes the current frame the first of a new shot: the tracks of the old
  // one (and its recovery keyframe) end here; the caller detects fresh ones.
  void StartShotAtThisFrame(FrameTracks* out, std::vector<cv::Point2f>* points,
                            std::vector<long>* ids) {
    out->boundary = ShotBoundary::kCut;
    out->shot = ++shot;
    out->transition = false;
    out->recovered = false;
    out->jump = false;
    points->clear();
    ids->clear();
    DropTracks();
    shots.MarkCut();
    run_tracked = true;
    run_motion_px = 0;
    run_start_points.clear();
  }

  // New corners on the half-resolution pyramid level (4x cheaper than the
  // full working image; KLT does not need corners at full resolution, any
  // well-textured window tracks). pyrDown keeps the even rows and columns,
  // so level-1 pixel q sits exactly on level-0 pixel 2q.
  void TopUp(const cv::Mat& gray, const std::vector<cv::Mat>& pyramid,
             std::vector<cv::Point2f>* points, std::vector<long>* ids) {
    GridDetectorOptions detect;
    detect.grid_cols = options.grid_cols;
    detect.grid_rows = options.grid_rows;
    detect.per_cell = (options.max_tracks + options.grid_cols * options.grid_rows - 1) /
                      (options.grid_cols * options.grid_rows);
    const size_t n0 = points->size();
    const int max_new = options.max_tracks - static_cast<int>(n0);
    // pyramid = {level0, derivatives0, level1, derivatives1, ...}
    const bool half = pyramid.size() >= 3 && gray.cols >= 320 && gray.rows >= 180;
    if (half) {
      const cv::Mat& level1 = pyramid[2];
      detect.min_distance_px = options.min_distance_px / 2;
      detect.border_px = std::max(2, options.klt_window / 8);
      std::vector<cv::Point2f> existing;
      existing.reserve(n0);
      for (const cv::Point2f& p : *points) existing.emplace_back(p.x / 2, p.y / 2);
      std::vector<cv::Point2f> fresh;
      DetectGridCorners(level1, existing, max_new, detect, &fresh);
      for (const cv::Point2f& q : fresh) points->emplace_back(2 * q.x, 2 * q.y);
    } else {
      detect.min_distance_px = options.min_distance_px;
      detect.border_px = std::max(4, options.klt_window / 4);
      DetectGridCorners(gray, *points, max_new, detect, points);
    }
    for (size_t i = n0; i < points->size(); ++i) ids->push_back(next_id++);
  }

  // Descriptor matches land on whole-pixel corners of the current frame;
  // KLT from the keyframe point, started at the match, puts each re-linked
  // track at the sub-pixel position of the *same* physical point, with a
  // forward-backward check (also started at the known answer).
  void RefineRelinked(const std::vector<cv::Mat>& pyramid, cv::Size size, RelinkResult* r) const {
    std::vector<cv::Mat> key_pyramid;
    const int max_level = std::min(1, options.pyramid_levels - 1);
    cv::buildOpticalFlowPyramid(relinker.key_gray(), key_pyramid, Window(), max_level, true);
    PyramidLkOptions lk = LkOptions();
    lk.max_level = max_level;
    std::vector<cv::Point2f> refined = r->points, back = r->key_points;
    std::vector<unsigned char> ok_f, ok_b;
    PyramidLk(key_pyramid, pyramid, r->key_points, &refined, &ok_f, lk, true);
    PyramidLk(pyramid, key_pyramid, refined, &back, &ok_b, lk, true);
    const double fb2 = options.fb_threshold_px * options.fb_threshold_px;
    size_t kept = 0;
    for (size_t i = 0; i < refined.size(); ++i) {
      const cv::Point2f moved = refined[i] - r->points[i];
      const cv::Point2f e = back[i] - r->key_points[i];
      const cv::Point2f& p = refined[i];
      if (!ok_f[i] || !ok_b[i] || !(moved.dot(moved) <= 9.0) || !(e.dot(e) <= fb2) ||
          !(p.x >= 0 && p.y >= 0 && p.x <= size.width - 1 && p.y <= size.height - 1))
        continue;
      r->points[kept] = p;
      r->ids[kept] = r->ids[i];
      r->key_points[kept] = r->key_points[i];
      ++kept;
    }
    r->points.resize(kept);
    r->ids.resize(kept);
    r->key_points.resize(kept);
  }

  // RANSAC homography from -> points; keeps its inliers if they are a clear
  // majority (>= 8 and >= half), else drops everything.
  static void KeepMutuallyConsistent(const std::vector<cv::Point2f>& from,
                                     std::vector<cv::Point2f>* points, std::vector<long>* ids) {
    std::vector<unsigned char> inlier;
    cv::Mat h;
    if (points->size() >= 8) h = cv::findHomography(from, *points, cv::RANSAC, 2.0, inlier);
    size_t n_in = 0;
    for (unsigned char b : inlier) n_in += b != 0;
    if (h.empty() || n_in < 8 || 2 * n_in < points->size()) {
      points->clear();
      ids->clear();
      return;
    }
    KeepTracksIf(points, ids, [&](size_t i) { return inlier[i] != 0; });
  }

  // Constant velocity: each point is expected where its last displacement
  // takes it; points without one (new detections, re-links) move by the
  // median of the others. Why: KLT started at zero displacement has to find
  // a whip pan's 100+ px per frame through the pyramid alone, and on the
  // blurred pictures it settles short (an 80 deg whip at 1280 px lost 6
  // degrees); the previous frame's motion is a far closer start.
  // False (KLT starts at zero motion, as without it) when the picture moved
  // less than a KLT window last frame (the pyramid finds that from zero, and
  // a start carrying last frame's tracking noise gains nothing), or when the
  // last two frames' median motions differ by more than half the last (a
  // shake back and forth: the last motion is no guide to the next), or when
  // either is unknown (a shot's first frames, after a collapse).
  // Over `step` frames (skipped frames in between) the motion is `step`
  // times a frame's.
  bool PredictMotion(std::vector<cv::Point2f>* predicted) const {
    if (!std::isfinite(motion_last.x) || !std::isfinite(motion_before.x) ||
        prev_velocity.size() != prev_points.size())
      return false;
    const double last = std::hypot(motion_last.x, motion_last.y);
    if (last * step < options.klt_window) return false;
    const cv::Point2f change = motion_last - motion_before;
    if (std::hypot(change.x, change.y) > 0.5 * last) return false;
    // Over skipped frames the change of velocity adds up (k (k + 1) / 2 a):
    // a whip pan slowing down overshoots a constant-velocity start.
    FillPredicted(predicted, /*accelerating=*/step > 1);
    return true;
  }

  // Each point's last velocity (or the median) times `step`; with
  // `accelerating`, plus the change of the median velocity over the last
  // frame kept up over the `step` frames: sum_{j=1..step} j = step (step + 1) / 2.
  void FillPredicted(std::vector<cv::Point2f>* predicted, bool accelerating = false) const {
    predicted->resize(prev_points.size());
    const float k = static_cast<float>(step);
    cv::Point2f extra(0, 0);
    if (accelerating && std::isfinite(motion_before.x))
      extra = (motion_last - motion_before) * (0.5f * k * (k + 1));
    for (size_t i = 0; i < prev_points.size(); ++i)
      (*predicted)[i] = k * (std::isfinite(prev_velocity[i].x) ? prev_velocity[i] : motion_last) + extra;
  }

  // KLT from zero motion lost most tracks (a collapse) although the picture
  // moved a KLT window or more last frame: the motion changed too much for
  // PredictMotion to trust it (a whip pan speeding up), but the last motion
  // is still a far closer start than zero for the tracks lost.
  bool RetryWithLastMotion(const std::vector<char>& ok) const {
    if (!std::isfinite(motion_last.x) || prev_velocity.size() != prev_points.size() ||
        prev_points.size() < kMinTracksForCollapse)
      return false;
    if (std::hypot(motion_last.x, motion_last.y) * step < options.klt_window) return false;
    const size_t kept = static_cast<size_t>(std::count(ok.begin(), ok.end(), 1));
    return kept < kCollapseFraction * static_cast<double>(prev_points.size());
  }

  // The median of the known velocities (x NaN when none is known).
  static cv::Point2f MedianMotion(const std::vector<cv::Point2f>& velocity) {
    std::vector<float> vx, vy;
    for (const cv::Point2f& v : velocity)
      if (std::isfinite(v.x)) {
        vx.push_back(v.x);
        vy.push_back(v.y);
      }
    if (vx.empty()) return {kNoMotion, kNoMotion};
    return {Quantile(std::move(vx), 0.5), Quantile(std::move(vy), 0.5)};
  }

  // KLT from the previous pyramid to `pyramid`, forward then backward.
  void Track(const std::vector<cv::Mat>& pyramid, cv::Size size, std::vector<cv::Point2f>* points,
             std::vector<long>* ids, std::vector<cv::Point2f>* from) {
    points->clear();
    ids->clear();
    from->clear();
    if (prev_points.empty() || prev_pyramid.empty() || prev_size != size) return;
    std::vector<cv::Point2f> predicted;
    const bool predict = options.klt_predict && PredictMotion(&predicted);
    std::vector<cv::Point2f> tracked;
    std::vector<char> ok = TrackFrom(pyramid, size, prev_points, predict ? &predicted : nullptr, &tracked);
    // A track the prediction lost (the motion changed: a stop, a jolt) gets
    // the search from zero motion too; after a collapse from zero motion,
    // the lost ones get the prediction.
    const bool retry_predicted = options.klt_predict && !predict && RetryWithLastMotion(ok);
    if (predict || retry_predicted) {
      if (retry_predicted) FillPredicted(&predicted, /*accelerating=*/true);
      std::vector<size_t> lost;
      std::vector<cv::Point2f> lost_points, lost_predicted, retried;
      for (size_t i = 0; i < ok.size(); ++i)
        if (!ok[i]) {
          lost.push_back(i);
          lost_points.push_back(prev_points[i]);
          if (retry_predicted) lost_predicted.push_back(predicted[i]);
        }
      const std::vector<char> ok_retried =
          TrackFrom(pyramid, size, lost_points, retry_predicted ? &lost_predicted : nullptr, &retried);
      for (size_t k = 0; k < lost.size(); ++k)
        if (ok_retried[k]) {
          ok[lost[k]] = 1;
          tracked[lost[k]] = retried[k];
        }
    }
    for (size_t i = 0; i < prev_points.size(); ++i) {
      if (!ok[i]) continue;
      points->push_back(tracked[i]);
      ids->push_back(prev_ids[i]);
      from->push_back(prev_points[i]);
    }
  }

  // KLT of `starts` from the previous pyramid to `pyramid` (from start +
  // offset[i] when given, else from zero motion) and back; ok[i]: both
  // converged, inside the image, forward-backward error within the limit.
  std::vector<char> TrackFrom(const std::vector<cv::Mat>& pyramid, cv::Size size,
                              const std::vector<cv::Point2f>& starts, const std::vector<cv::Point2f>* offset,
                              std::vector<cv::Point2f>* tracked) const {
    const PyramidLkOptions lk = LkOptions();
    std::vector<cv::Point2f> forward, backward;
    std::vector<unsigned char> ok_f, ok_b;
    if (offset)
      for (size_t i = 0; i < starts.size(); ++i) forward.push_back(starts[i] + (*offset)[i]);
    PyramidLk(prev_pyramid, pyramid, starts, &forward, &ok_f, lk, offset != nullptr);
    if (offset)
      for (size_t i = 0; i < forward.size(); ++i) backward.push_back(forward[i] - (*offset)[i]);
    PyramidLk(pyramid, prev_pyramid, forward, &backward, &ok_b, lk, offset != nullptr);
    const float fb2 = static_cast<float>(options.fb_threshold_px * options.fb_threshold_px);
    const float max_x = static_cast<float>(size.width - 1), max_y = static_cast<float>(size.height - 1);
    std::vector<char> ok(starts.size(), 0);
    for (size_t i = 0; i < starts.size(); ++i) {
      if (!ok_f[i] || !ok_b[i]) continue;
      const cv::Point2f& p = forward[i];
      if (!(p.x >= 0 && p.y >= 0 && p.x <= max_x && p.y <= max_y)) continue;
      const cv::Point2f e = backward[i] - starts[i];
      ok[i] = e.x * e.x + e.y * e.y <= fb2;  // also rejects NaN
    }
    *tracked = std::move(forward);
    return ok;
  }

  // One frame's tracking, as the steps of Process() pass it on.
  struct FrameWork {
    std::vector<cv::Mat> pyramid;
    cv::Size size;
    std::vector<cv::Point2f> points, from;  // tracked points and where they came from
    std::vector<long> ids;
    bool had_tracks = false;  // the previous frame had tracks (false: the shot's first tracked frame)
    int flat_version = 0;     // the vignetting field the pyramid was built with (0: none)
    size_t before = 0;        // the previous frame's tracks
    size_t survived = 0;      // KLT survivors (after the collapse's consistency check)
    size_t relinked = 0;      // tracks the descriptors brought back
    bool collapsed = false;
    RelinkResult relink;
    std::unordered_map<long, cv::Point2f> moved;  // this frame's KLT displacement per id (klt_predict)
    std::vector<float> klt_disp;                  // for the transition-run statistics
  };

  // KLT of each track from its anchor frame to this one at the finest level
  // only, started at its frame-to-frame position (the drift to correct is a
  // pixel or two, within one level's reach), with a forward-backward check.
  // refined[i] is NaN where that failed or the track has no older anchor.
  std::vector<cv::Point2f> TrackFromAnchors(const FrameWork& w) {
    const cv::Point2f none(kNoMotion, kNoMotion);
    std::vector<cv::Point2f> refined(w.points.size(), none);
    std::unordered_map<int, std::vector<size_t>> by_anchor;
    for (size_t i = 0; i < w.points.size(); ++i) {
      const auto it = anchors.find(w.ids[i]);
      if (it != anchors.end() && it->second.frame != prev_tracked_index) by_anchor[it->second.frame].push_back(i);
    }
    PyramidLkOptions lk = LkOptions();
    lk.max_level = 0;
    const std::vector<cv::Mat> level0(w.pyramid.begin(), w.pyramid.begin() + 2);
    const float fb2 = static_cast<float>(options.fb_threshold_px * options.fb_threshold_px);
    if (options.klt_anchor_affine) return AlignToAnchors(w, by_anchor);
    for (const auto& [frame, tracks] : by_anchor) {
      const std::vector<cv::Mat>& anchor_level = anchor_levels.at(frame);
      std::vector<cv::Point2f> from, to;
      for (size_t i : tracks) {
        from.push_back(anchors.at(w.ids[i]).point);
        to.push_back(w.points[i]);
      }
      std::vector<cv::Point2f> back = from;
      std::vector<unsigned char> ok_f, ok_b;
      PyramidLk(anchor_level, level0, from, &to, &ok_f, lk, true);
      PyramidLk(level0, anchor_level, to, &back, &ok_b, lk, true);
      for (size_t k = 0; k < tracks.size(); ++k) {
        const cv::Point2f e = back[k] - from[k];
        const cv::Point2f& p = to[k];
        if (ok_f[k] && ok_b[k] && e.x * e.x + e.y * e.y <= fb2 && p.x >= 0 && p.y >= 0 &&
            p.x <= w.size.width - 1 && p.y <= w.size.height - 1)
          refined[tracks[k]] = p;
      }
    }
    return refined;
  }

  // The affine drift bound: each track's patch at its anchor aligned by an
  // affine warp (AlignAffinePatch) from its KLT position and last warp.
  std::vector<cv::Point2f> AlignToAnchors(const FrameWork& w,
                                          const std::unordered_map<int, std::vector<size_t>>& by_anchor) {
    std::vector<cv::Point2f> refined(w.points.size(), cv::Point2f(kNoMotion, kNoMotion));
    const int half = options.klt_window / 2;
    for (const auto& [frame, tracks] : by_anchor) {
      const cv::Mat& anchor_image = anchor_levels.at(frame)[0];
      for (size_t i : tracks) {
        TrackAnchor& a = anchors.at(w.ids[i]);
        AffinePatchFit start;
        start.position = w.points[i];
        start.linear = a.linear;
        const AffinePatchFit fit = AlignAffinePatch(anchor_image, a.point, w.pyramid[0], start, half);
        if (!fit.ok) {
          // No longer aligns; a window at the image border measured nothing
          // (the track keeps its KLT position and is re-anchored).
          a.residual = fit.inside ? -1 : 0;
          continue;
        }
        refined[i] = fit.position;
        a.linear = fit.linear;
        a.residual = fit.residual;
      }
    }
    return refined;
  }

  // Median + 3 robust sigmas (1.4826 MAD) of a frame's values: beyond it a
  // value is an outlier among the frame's tracks.
  static float RobustUpperBound(std::vector<float> values) {
    const float median = Quantile(values, 0.5);
    for (float& v : values) v = std::abs(v - median);
    return median + 3 * 1.4826f * Quantile(std::move(values), 0.5);
  }

  float AnchorResidualBound(const FrameWork& w, const std::vector<cv::Point2f>& refined) const {
    std::vector<float> residuals;
    for (size_t i = 0; i < w.points.size(); ++i)
      if (std::isfinite(refined[i].x)) residuals.push_back(anchors.at(w.ids[i]).residual);
    return residuals.empty() ? 0.f
                             : std::max(kAnchorResidualFloor, RobustUpperBound(std::move(residuals)));
  }

  // Affine check: a patch that no longer aligns with its first appearance,
  // or whose residual is an outlier among the frame's, has drifted off its
  // point (re-anchoring it would keep the drift): the track ends.
  bool LostItsAnchor(long id, bool aligned, float residual_bound) const {
    const auto it = anchors.find(id);
    if (it == anchors.end()) return false;
    return aligned ? it->second.residual > residual_bound : it->second.residual < 0;
  }

  // The drift bound: tracks move to their anchored positions; a correction
  // beyond median + 3 robust sigmas of this frame's corrections (and
  // klt_anchor_min_px) marks a track that slipped onto another point: it
  // ends here. A track whose anchor no longer matches (the check failed)
  // keeps its KLT position and is re-anchored on this frame.
  void BoundDrift(FrameWork* w) {
    if (options.klt_anchor_frames <= 0 || w->points.empty()) return;
    const std::vector<cv::Point2f> refined = TrackFromAnchors(*w);
    std::vector<float> correction(w->points.size(), -1.f), measured;
    for (size_t i = 0; i < w->points.size(); ++i) {
      if (!std::isfinite(refined[i].x)) continue;
      correction[i] = static_cast<float>(cv::norm(refined[i] - w->points[i]));
      measured.push_back(correction[i]);
    }
    if (measured.empty()) return;
    const float bound = std::max(static_cast<float>(options.klt_anchor_min_px), RobustUpperBound(measured));
    const float residual_bound = options.klt_anchor_affine ? AnchorResidualBound(*w, refined) : 0.f;
    size_t kept = 0;
    for (size_t i = 0; i < w->points.size(); ++i) {
      const bool refined_ok = correction[i] >= 0;
      if (correction[i] > bound || (options.klt_anchor_affine && LostItsAnchor(w->ids[i], refined_ok, residual_bound))) {
        anchors.erase(w->ids[i]);
        continue;
      }
      if (refined_ok) w->points[i] = refined[i];
      else anchors.erase(w->ids[i]);  // re-anchored on this frame (UpdateAnchors)
      w->points[kept] = w->points[i];
      w->ids[kept] = w->ids[i];
      w->from[kept] = w->from[i];
      ++kept;
    }
    w->points.resize(kept);
    w->ids.resize(kept);
    w->from.resize(kept);
  }

  // After the frame's tracks are final: new, re-linked and re-anchored
  // tracks, and those whose anchor is klt_anchor_frames old, are anchored
  // on this frame; anchors of ended tracks and unused anchor frames go.
  void UpdateAnchors(int frame_index, const FrameWork& w) {
    if (options.klt_anchor_frames <= 0) return;
    std::unordered_map<long, TrackAnchor> next;
    next.reserve(w.ids.size());
    bool anchored_here = false;
    for (size_t i = 0; i < w.ids.size(); ++i) {
      const auto it = anchors.find(w.ids[i]);
      if (it != anchors.end() && frame_index - it->second.frame < options.klt_anchor_frames) {
        next.emplace(w.ids[i], it->second);
      } else {
        next.emplace(w.ids[i], TrackAnchor{w.points[i], frame_index});
        anchored_here = true;
      }
    }
    anchors = std::move(next);
    std::unordered_set<int> used;
    for (const auto& [id, a] : anchors) used.insert(a.frame);
    for (auto it = anchor_levels.begin(); it != anchor_levels.end();)
      it = used.count(it->first) ? std::next(it) : anchor_levels.erase(it);
    if (anchored_here && w.pyramid.size() >= 2)
      anchor_levels[frame_index] = {w.pyramid[0], w.pyramid[1]};
  }

  // Whether one homography moves the picture as the tracks moved: most of
  // them within a pixel (KLT's own precision). A move with parallax (a
  // crane, a traveling) is not one homography, and chained over a long run
  // its prediction drifts until the moved picture looks like another one:
  // such a run is no evidence of a dissolve either way.
  static bool ExplainsThePicture(const cv::Matx33d& h, const std::vector<cv::Point2f>& from,
                                 const std::vector<cv::Point2f>& to, double tolerance_px = 1.0) {
    size_t close = 0;
    for (size_t i = 0; i < from.size(); ++i) {
      const cv::Vec3d p = h * cv::Vec3d(from[i].x, from[i].y, 1.0);
      const double dx = p[0] / p[2] - to[i].x, dy = p[1] / p[2] - to[i].y;
      close += dx * dx + dy * dy <= tolerance_px * tolerance_px;
    }
    return close >= kPictureExplained * static_cast<double>(from.size());
  }

  // Whether the chained run motion still puts the tracks that lived through
  // the whole run where they are, to one pixel of the picture comparison's
  // layout (MovedPictureChange cannot see a drift under that, and a larger
  // one decorrelates its cells): a crane's parallax passes each frame's
  // 1 px test yet drifts by several layout pixels over a long run. Too few
  // such tracks to tell: the per-frame tests stand.
  static double LayoutPixel(cv::Size working) { return double(working.width) / kLayoutWidth; }

  bool ChainStillExplainsTheRun(const FrameWork& w) const {
    std::vector<cv::Point2f> from, to;
    for (size_t i = 0; i < w.survived; ++i) {
      const auto start = run_start_points.find(w.ids[i]);
      if (start == run_start_points.end()) continue;
      from.push_back(start->second);
      to.push_back(w.points[i]);
    }
    if (from.size() < kMinTracksForCollapse) return true;
    return ExplainsThePicture(run_motion, from, to, LayoutPixel(w.size));
  }

  // One tracked frame of a run: its KLT motion joins the chain.
  void ChainRunMotion(const FrameWork& w) {
    if (!run_chain) return;
    if (w.collapsed || w.survived < kMinTracksForCollapse || w.from.size() < w.survived) {
      run_chain = false;
      return;
    }
    // At most ~kChainPoints of them, spread along the list (the grid
    // detector's order): plenty for 8 parameters, a third of RANSAC's cost.
    std::vector<cv::Point2f> from, to;
    const size_t stride = std::max<size_t>(1, w.survived / kChainPoints);
    for (size_t i = 0; i < w.survived; i += stride) {
      from.push_back(w.from[i]);
      to.push_back(w.points[i]);
    }
    const cv::Mat h = cv::findHomography(from, to, cv::RANSAC, 3.0);
    if (h.empty() || !ExplainsThePicture(cv::Matx33d(h), from, to)) {
      run_chain = false;
      return;
    }
    if (run_start_points.empty())
      for (size_t i = 0; i < w.survived; ++i) run_start_points.emplace(w.ids[i], w.from[i]);
    run_motion = cv::Matx33d(h) * run_motion;
    if (!ChainStillExplainsTheRun(w)) run_chain = false;
  }

  // The shot boundary of this frame: a cut or fade starts a new shot unless
  // tracked camera motion or a fade through black within the shot explains it.
  void DecideBoundary(const Frame& frame, const ShotDecision& decision, FrameTracks* out) {
    cut_may_be_a_break = break_began = false;
    if (first) {
      out->boundary = ShotBoundary::kStart;
      first = false;
    } else if (Stills()) {
      // Stills: a new view changes the histogram; the descriptor link decides.
    } else if (decision.boundary == ShotBoundary::kFade && RunWasCameraMotion(frame.gray.size())) {
      // Gradual change explained by tracked motion: same shot, keep tracking.
    } else if (decision.boundary == ShotBoundary::kFade && after_blank &&
               options.descriptor_recovery && relinker.has_keyframe() &&
               (bridge = relinker.Relink(frame.gray, 2 * options.max_tracks)).points.size() >=
                   kMinTracksForCollapse &&
               !bridge.current_from_key.empty()) {
      // Fade through black within one shot: the picture after the black
      // matches the last good frame before it, so the shot goes on and the
      // re-linked tracks carry the motion made in the dark.
    } else if (decision.boundary != ShotBoundary::kNone ||
               IsLookAlikeDissolve(decision, frame.gray.size())) {
      out->boundary = decision.boundary != ShotBoundary::kNone ? decision.boundary : ShotBoundary::kFade;
      cut_may_be_a_break = CutMayBeABreak(decision);
      if (cut_may_be_a_break && break_anchor.empty()) StartBreak(frame);
      DescribedFrame anchor = cut_may_be_a_break ? std::move(break_anchor) : DescribedFrame{};
      ++shot;
      DropTracks();
      bridge = {};
      break_anchor = std::move(anchor);
    }
    if (!decision.transition) {
      run_tracked = true;
      run_motion_px = 0;
      run_motion = cv::Matx33d::eye();
      run_chain = true;
      run_start_points.clear();
      run_before_layout = shots.layout();  // the picture before a run starting next frame
    }
    out->shot = shot;
    out->blank = decision.blank;
    out->transition = decision.transition;
  }

  // Tracks end at a blank frame, but the relinker keeps the last good frame
  // before the black, to bridge a fade through black (DecideBoundary).
  void EndTracksAtBlank() {
    prev_pyramid.clear();
    prev_points.clear();
    prev_velocity.clear();
    motion_last = motion_before = {kNoMotion, kNoMotion};
    prev_ids.clear();
    anchors.clear();
    anchor_levels.clear();
    after_blank = true;
  }

  // The frame KLT tracks: in a fade, matched to the contrast of the last
  // tracked picture (itself matched in a fade), so LK sees one brightness.
  cv::Mat ContrastMatchedToLast(const cv::Mat& gray) {
    if (!options.match_fade_contrast) return gray;
    cv::Scalar mean, stddev;
    cv::meanStdDev(gray, mean, stddev);
    double gain = 1;
    const cv::Mat tracked = prev_pyramid.empty()
                                ? gray
                                : ContrastMatched(gray, mean[0], stddev[0], last_mean, last_stddev, &gain);
    if (gain == 1) {
      last_mean = mean[0];
      last_stddev = stddev[0];
    } else {
      RememberContrast(tracked);  // as matched: clipped at black and white
    }
    return tracked;
  }

  void RememberContrast(const cv::Mat& tracked) {
    cv::Scalar mean, stddev;
    cv::meanStdDev(tracked, mean, stddev);
    last_mean = mean[0];
    last_stddev = stddev[0];
  }

  // The frame as KLT sees it: divided by the vignetting once one is found.
  // The raw frame is kept while the field may still change (the next step
  // rebuilds this frame's pyramid with the new field).
  cv::Mat FlatFieldedPicture(const cv::Mat& gray, FrameWork* w) {
    if (options.flat_field_vignetting && !vignetting_decided) last_raw = gray;
    if (!vignetting.found) return gray;
    if (flat_gain.size() != gray.size() || flat_gain_version != flat_version) {
      flat_gain = FlatFieldGain(vignetting, gray.size());
      flat_gain_version = flat_version;
    }
    w->flat_version = flat_version;
    return FlatFielded(gray, flat_gain);
  }

  // The field changed after the last frame's pyramid was built: that frame
  // is rebuilt with it, so both sides of the step see one picture.
  void FlatFieldPrevious(cv::Size size) {
    if (prev_flat_version == flat_version || prev_pyramid.empty() || prev_raw.size() != size) return;
    FrameWork redo;
    std::vector<cv::Mat> rebuilt;  // fresh buffers: an anchor may hold the old level 0
    cv::buildOpticalFlowPyramid(FlatFieldedPicture(prev_raw, &redo), rebuilt, Window(), options.pyramid_levels - 1,
                                true);
    prev_pyramid = std::move(rebuilt);
    prev_flat_version = flat_version;
  }

  // The pairs that follow the step's dominant motion (RANSAC homography,
  // kVignettingInlierPx): a mover's tracks (a person crossing, turning in
  // the light) change brightness together and would read as a field.
  static bool KeepDominantMotion(std::vector<cv::Point2f>* from, std::vector<cv::Point2f>* to) {
    if (from->size() < 8) return false;
    std::vector<unsigned char> inlier;
    if (cv::findHomography(*from, *to, cv::RANSAC, kVignettingInlierPx, inlier).empty()) return false;
    size_t kept = 0;
    for (size_t i = 0; i < from->size(); ++i)
      if (inlier[i]) {
        (*from)[kept] = (*from)[i];
        (*to)[kept++] = (*to)[i];
      }
    from->resize(kept);
    to->resize(kept);
    return kept >= 8;
  }

  // The tracked pairs' brightness change into the vignetting fit (on the
  // pictures KLT tracked: once a field is found, what is left of it);
  // every kVignettingDecideEvery steps a decision: a field found is taken,
  // then refined by what is left (KLT, pulled by the fall-off, reads part
  // of it as motion, so the first fit falls short), until nothing
  // significant is left or kMaxVignettingRefinements.
  void FitVignetting(const Frame& frame, const FrameWork& w) {
    if (!options.flat_field_vignetting || vignetting_decided || w.from.empty() || prev_flat_version != w.flat_version)
      return;
    const int level = std::min<int>({kBrightnessLevel, static_cast<int>(prev_pyramid.size() / 2) - 1,
                                     static_cast<int>(w.pyramid.size() / 2) - 1});
    if (level < 0) return;
    std::vector<cv::Point2f> from = w.from, to = w.points;
    if (!KeepDominantMotion(&from, &to)) return;
    vignetting_fit.AddStep(prev_pyramid[2 * level], w.pyramid[2 * level], std::ldexp(1.0, level), from, to, w.size);
    if (vignetting_fit.pairs() < next_vignetting_decision && !vignetting_fit.full()) return;
    next_vignetting_decision = static_cast<size_t>(kVignettingDecisionGrowth * vignetting_fit.pairs());
    const VignettingModel m = vignetting_fit.Decide(vignetting.found ? kMinResidualFalloff : kMinCornerFalloff);
    if (m.found) {
      vignetting.a += m.a;
      vignetting.b += m.b;
      vignetting.found = true;
      ++flat_version;
      vignetting_fit = VignettingFit();
      next_vignetting_decision = kMinVignettingPairs;
    }
    if (m.found ? flat_version >= kMaxVignettingRefinements : vignetting_fit.full()) vignetting_decided = true;
    if (m.found || vignetting_decided)
      Record(diagnostics, "vignetting", {{"frame", frame.index}, {"found", vignetting.found}, {"a", vignetting.a},
                                         {"b", vignetting.b}, {"corner_gain", vignetting.corner_gain()},
                                         {"residual_corner_gain", m.corner_gain()}, {"refinement", flat_version}});
  }

  // KLT from the last frame, with the displacements the prediction and the
  // transition-run statistics need.
  void TrackFromLastFrame(const Frame& frame, bool transition, FrameWork* w) {
    w->size = frame.gray.size();
    w->pyramid = std::move(spare_pyramid);
    FlatFieldPrevious(w->size);
    cv::buildOpticalFlowPyramid(ContrastMatchedToLast(FlatFieldedPicture(frame.gray, w)), w->pyramid, Window(),
                                options.pyramid_levels - 1, true);
    w->had_tracks = !prev_points.empty();
    w->before = prev_points.size();
    Track(w->pyramid, w->size, &w->points, &w->ids, &w->from);
    FitVignetting(frame, *w);
    BoundDrift(w);
    if (options.klt_predict)  // per frame (x 1 exactly when no frame was skipped)
      for (size_t i = 0; i < w->points.size(); ++i)
        w->moved.emplace(w->ids[i], (w->points[i] - w->from[i]) * (1.0f / step));
    w->survived = w->points.size();
    if (transition)
      for (size_t i = 0; i < w->points.size(); ++i)
        w->klt_disp.push_back(static_cast<float>(cv::norm(w->points[i] - w->from[i])));
    w->collapsed = w->had_tracks && w->before >= kMinTracksForCollapse && w->survived < kCollapseFraction * w->before;
    if (transition) ChainRunMotion(*w);
  }

  // The re-links across a fade through black, refined against the keyframe
  // on a copy of this frame with the keyframe's mean and contrast (a fade-in
  // is dimmer, and LK assumes constant brightness). Too few refined: the
  // matched corners.
  RelinkResult BridgeFade(const Frame& frame, cv::Size size) {
    RelinkResult r = std::move(bridge);
    bridge = {};
    cv::Scalar key_mean, key_std, cur_mean, cur_std;
    cv::meanStdDev(relinker.key_gray(), key_mean, key_std);
    cv::meanStdDev(frame.gray, cur_mean, cur_std);
    const double gain = key_std[0] / std::max(cur_std[0], 1e-3);
    cv::Mat matched;
    frame.gray.convertTo(matched, -1, gain, key_mean[0] - gain * cur_mean[0]);
    std::vector<cv::Mat> matched_pyramid;
    cv::buildOpticalFlowPyramid(matched, matched_pyramid, Window(), options.pyramid_levels - 1, true);
    RelinkResult refined = r;
    RefineRelinked(matched_pyramid, size, &refined);
    if (refined.points.size() >= kMinTracksForCollapse) r = std::move(refined);
    return r;
  }

  // Descriptor recovery (after a fade through black, or a collapse), and
  // the re-linked tracks added to the survivors.
  void Recover(const Frame& frame, FrameTracks* out, FrameWork* w) {
    if (!bridge.points.empty()) {
      w->relink = BridgeFade(frame, w->size);
    } else if (w->collapsed && options.descriptor_recovery && relinker.has_keyframe()) {
      w->relink = relinker.Relink(frame.gray, 2 * options.max_tracks);
      if (!w->relink.points.empty()) RefineRelinked(w->pyramid, w->size, &w->relink);
    }
    if (w->collapsed) {
      // The few KLT "survivors" of a collapse are suspect: LK can converge
      // to a look-alike patch in both directions. Keep those that agree with
      // the recovered motion, or, without one, with each other.
      if (!w->relink.current_from_key.empty())
        relinker.KeepConsistent(w->relink.current_from_key, 3.0, &w->points, &w->ids);
      else
        KeepMutuallyConsistent(w->from, &w->points, &w->ids);
      w->survived = w->points.size();
    }
    const RelinkResult& r = w->relink;
    if (r.points.empty()) return;
    std::unordered_set<long> alive(w->ids.begin(), w->ids.end());
    for (size_t i = 0; i < r.points.size(); ++i) {
      if (alive.count(r.ids[i])) continue;
      w->points.push_back(r.points[i]);
      w->ids.push_back(r.ids[i]);
      alive.insert(r.ids[i]);
      ++w->relinked;
    }
    out->recovered = w->relinked > 0;
  }

  // A look-alike cut starts a new shot here; otherwise a transition-flagged
  // frame adds to its run's statistics.
  void CheckCut(const Frame& frame, const ShotDecision& decision, FrameTracks* out, FrameWork* w) {
    if (Wants(diagnostics, "cut_cues"))
      diagnostics->Record("cut_cues", {{"frame", frame.index}, {"distance", decision.distance},
                                       {"spike", decision.spike}, {"transition", decision.transition}, {"continuity", decision.continuity},
                                       {"tracks", w->before}, {"kept", w->survived}, {"collapsed", w->collapsed},
                                       {"relinked", w->relinked}, {"relink_failed", w->relink.current_from_key.empty()}});
    if (w->had_tracks && IsLookAlikeCut(decision, w->collapsed, w->before, w->survived, w->relink)) {
      StartShotAtThisFrame(out, &w->points, &w->ids);
      w->had_tracks = false;  // counts as the shot's first tracked frame
    } else if (decision.transition) {
      const RelinkResult& r = w->relink;
      if (w->relinked > 0 && w->klt_disp.size() < kMotionRunSurvival * static_cast<double>(w->before)) {
        w->klt_disp.clear();  // KLT collapsed: the re-links carry the motion
        for (size_t i = 0; i < r.points.size(); ++i)
          w->klt_disp.push_back(static_cast<float>(cv::norm(r.points[i] - r.key_points[i])));
      }
      AccumulateRun(w->before, w->survived + w->relinked, std::move(w->klt_disp), frame.gray.cols);
    }
  }

  // Top up when well below max_tracks and either the count fell since the
  // last top-up (tracks died) or a while has passed (new texture may have
  // come into view). Low-texture pictures never reach max_tracks; without
  // this they would pay for a full detection every frame.
  void TopUpIfThin(const Frame& frame, FrameWork* w) {
    ++frames_since_detect;
    if (descriptor_mode) return;  // DescribedTopUp added the frame's SIFT keypoints
    if (!(w->points.size() < 0.9 * options.max_tracks &&
          (!w->had_tracks || w->points.size() < 0.9 * tracks_after_detect || frames_since_detect >= 8)))
      return;
    TopUp(frame.gray, w->pyramid, &w->points, &w->ids);
    tracks_after_detect = w->points.size();
    frames_since_detect = 0;
  }

  // The tracks in decoded-frame pixels (pixel-centre convention).
  static void WriteTracks(const Frame& frame, const FrameWork& w, FrameTracks* out) {
    const double sx = frame.decoded_width > 0 ? double(w.size.width) / frame.decoded_width : frame.scale;
    const double sy = frame.decoded_height > 0 ? double(w.size.height) / frame.decoded_height : frame.scale;
    out->points.reserve(w.points.size());
    for (size_t i = 0; i < w.points.size(); ++i) {
      TrackPoint tp;
      tp.track_id = w.ids[i];
      tp.px = Eigen::Vector2d((w.points[i].x + 0.5) / sx - 0.5, (w.points[i].y + 0.5) / sy - 0.5);
      out->points.push_back(tp);
    }
  }

  // This frame becomes the previous one for the next.
  void KeepForNextFrame(FrameWork* w) {
    spare_pyramid = std::move(prev_pyramid);
    // An anchor frame's finest level is kept: the next pyramid must not reuse it.
    if (spare_pyramid.size() >= 2 && anchor_levels.count(prev_tracked_index)) {
      spare_pyramid[0] = cv::Mat();
      spare_pyramid[1] = cv::Mat();
    }
    prev_pyramid = std::move(w->pyramid);
    prev_size = w->size;
    prev_flat_version = w->flat_version;
    prev_raw = last_raw;
    if (options.klt_predict) {
      prev_velocity.assign(w->ids.size(), cv::Point2f(kNoMotion, kNoMotion));
      for (size_t i = 0; i < w->ids.size(); ++i) {
        const auto it = w->moved.find(w->ids[i]);
        if (it != w->moved.end()) prev_velocity[i] = it->second;
      }
      motion_before = motion_last;
      motion_last = MedianMotion(prev_velocity);
    }
    prev_points = std::move(w->points);
    prev_ids = std::move(w->ids);
  }

  // One "descriptor_links" record per descriptor link tried (report detail).
  void RecordLink(const Frame& frame, const char* step, const LinkResult& link, size_t taken) const {
    static const char* kModel[] = {"none", "homography", "fundamental"};
    Record(diagnostics, "descriptor_links",
           {{"frame", frame.index}, {"step", step}, {"model", kModel[static_cast<int>(link.model)]},
            {"verified_matches", link.verified_matches}, {"carried", link.points.size()},
            {"median_motion_px", link.median_motion_px}, {"tracks_taken", taken}, {"guided", link.guided}});
  }

  // New tracks on the current frame's SIFT keypoints (strongest first, not
  // on a track: SIFT repeats a keypoint with a second orientation), so that
  // the next frame's descriptors can continue every one of them (up to the
  // linker's 2 x max_tracks keypoints: still images are few, and a pair of
  // views far apart shares only a fraction of them); `cur` learns which
  // keypoint each track sits on.
  void DescribedTopUp(DescribedFrame* cur, FrameWork* w) {
    std::vector<int> order(cur->keypoints.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return cur->keypoints[a].response > cur->keypoints[b].response; });
    cv::Mat taken(w->size, CV_8U, cv::Scalar(0));
    const int radius = 1;
    for (const cv::Point2f& p : w->points) cv::circle(taken, p, radius, cv::Scalar(255), cv::FILLED);
    for (int k : order) {
      if (cur->point_of_keypoint[k] >= 0) continue;
      const cv::Point2f& p = cur->keypoints[k].pt;
      const cv::Point q(std::clamp(static_cast<int>(std::lround(p.x)), 0, w->size.width - 1),
                        std::clamp(static_cast<int>(std::lround(p.y)), 0, w->size.height - 1));
      if (taken.at<unsigned char>(q)) continue;
      cur->point_of_keypoint[k] = static_cast<int>(w->points.size());
      w->points.push_back(p);
      w->ids.push_back(next_id++);
      cv::circle(taken, p, radius, cv::Scalar(255), cv::FILLED);
    }
    cur->points = w->points;
    cur->ids = w->ids;
  }

  // The link's tracks become this frame's: the descriptor-carried ones
  // first (their indices are the link's point_of_keypoint), then the
  // frame's own tracks that agree with the verified geometry.
  void TakeLink(const LinkResult& link, const std::unordered_map<long, cv::Point2f>& key_by_id, FrameWork* w) {
    std::vector<cv::Point2f> points = link.points;
    std::vector<long> ids = link.ids;
    std::unordered_set<long> taken(ids.begin(), ids.end());
    size_t agreeing = 0;
    for (size_t i = 0; i < w->points.size(); ++i) {
      const auto it = key_by_id.find(w->ids[i]);
      if (taken.count(w->ids[i]) || it == key_by_id.end() || !linker.Agrees(link, it->second, w->points[i]))
        continue;
      points.push_back(w->points[i]);
      ids.push_back(w->ids[i]);
      ++agreeing;
    }
    w->points = std::move(points);
    w->ids = std::move(ids);
    w->survived = agreeing;
    w->relinked = link.points.size();
  }

  // KLT kept under 70 % of the tracks: link the frame to the last one (else
  // to the relinker's keyframe) by SIFT descriptors. When KLT's survivors
  // disagree with the verified geometry (under half agree: LK settled on
  // look-alikes, or nothing survived), the link's tracks replace them; if
  // its motion is beyond KLT's reach from zero motion (a KLT window), the
  // next frames are linked by descriptors too. Ordinary footage never gets
  // here (no SIFT cost); a whip pan that KLT follows keeps KLT's answer.
  void ProbeDescriptors(const Frame& frame, FrameTracks* out, FrameWork* w) {
    if (!options.descriptor_linking || !w->had_tracks || out->boundary == ShotBoundary::kCut ||
        w->before < kMinTracksForCollapse ||
        static_cast<double>(w->survived + w->relinked) >= kGoodSurvival * w->before || prev_pyramid.empty())
      return;
    DescribedFrame cur;
    cur.gray = frame.gray;
    linker.Describe(&cur);
    DescribedFrame key;
    key.gray = prev_pyramid[0];
    key.points = prev_points;
    key.ids = prev_ids;
    linker.Describe(&key);
    LinkResult link = linker.Link(key, cur);
    if (!link.ok() && relinker.has_keyframe() && relinker.key_gray().data != key.gray.data) {
      key.gray = relinker.key_gray();
      key.points = relinker.key_points();
      key.ids = relinker.key_ids();
      linker.Describe(&key);
      link = linker.Link(key, cur);
    }
    if (!link.ok()) return;
    std::unordered_map<long, cv::Point2f> key_by_id;
    for (size_t i = 0; i < key.ids.size(); ++i) key_by_id.emplace(key.ids[i], key.points[i]);
    size_t checked = 0, agree = 0;
    for (size_t i = 0; i < w->points.size(); ++i) {
      const auto it = key_by_id.find(w->ids[i]);
      if (it == key_by_id.end()) continue;
      ++checked;
      agree += linker.Agrees(link, it->second, w->points[i]);
    }
    if (StillsByEvidence(link)) stills_by_evidence = true;
    const bool klt_right = !stills_by_evidence && checked >= kMinTracksForCollapse && 2 * agree >= checked;
    RecordLink(frame, "probe", link, klt_right ? 0 : link.points.size());
    if (klt_right) return;
    // Stills: KLT's answers across the jump are not kept beside the keypoints'.
    TakeLink(link, stills_by_evidence ? std::unordered_map<long, cv::Point2f>{} : key_by_id, w);
    out->recovered = w->relinked > 0;
    if (link.median_motion_px < options.klt_window) return;
    out->jump = true;
    descriptor_mode = true;
    cur.point_of_keypoint = link.point_of_keypoint;
    // Stills by evidence: the shot's first link, no earlier still to link.
    std::deque<DescribedFrame>* views = ViewsToLink(stills_by_evidence, true);
    LinkEarlierViews(views, key.gray, &cur, w);
    DescribedTopUp(&cur, w);
    last_described = good_described = cur;
    last_link = link;
    KeepView(views, cur);
    if (!stills_by_evidence) return;
    // The shot's first frame, tracked before the evidence, is a still too.
    // (its picture copied: the pyramids' buffers are reused).
    if (key.gray.data == prev_pyramid[0].data) {
      key.gray = key.gray.clone();
      KeepStillsView(key, prev_tracked_index);
    }
    KeepStillsView(cur, frame.index);
  }

  // A video that is a sequence of stills: its shot's very first step already
  // jumps beyond KLT's reach (KLT lost over 30 % of the tracks, the verified
  // descriptor matches moved a KLT window or more). Consecutive video frames
  // sample a continuous motion and a shot starts within KLT's reach; a cut
  // into a whip pan blurs past what descriptors verify.
  bool StillsByEvidence(const LinkResult& link) const {
    return options.stills_by_evidence && shot_tracked_frames == 1 && link.ok() &&
           link.median_motion_px >= options.klt_window;
  }

  // Stills: a view links to the one before it, but a keypoint that view
  // missed (occluded, out of frame, below its cap) may be in the views
  // before; linking to them too continues those tracks (ids skip the
  // views that missed them) and spans weak links with more than the few
  // tracks one pair shares. Back from the last view (but `linked`, the
  // view already linked), until a view no longer links (those further
  // round share less); a current keypoint keeps the first track it joins.
  // A video's jump frame does the same with the shot's earlier views
  // (`shot_views`, `guided`): a jump often returns the camera to where
  // frames before it saw the scene (a cut-back, a lost stretch), and the
  // points those frames triangulated place it; their tracks are KLT
  // corners, carried by the guided KLT, taken where no track is yet.
  void LinkEarlierViews(std::deque<DescribedFrame>* views, const cv::Mat& linked, DescribedFrame* cur,
                        FrameWork* w) {
    const bool guided = views == &shot_views;
    std::unordered_set<long> taken(w->ids.begin(), w->ids.end());
    for (size_t back = 1; back <= views->size(); ++back) {
      DescribedFrame& view = (*views)[views->size() - back];
      if (view.gray.data == linked.data) continue;
      if (view.point_of_keypoint.empty()) linker.Describe(&view);
      const LinkResult earlier = linker.Link(view, *cur);
      if (!earlier.ok()) break;
      for (size_t k = 0; k < earlier.point_of_keypoint.size(); ++k) {
        const int i = earlier.point_of_keypoint[k];
        if (i < 0 || cur->point_of_keypoint[k] >= 0 || taken.count(earlier.ids[i])) continue;
        cur->point_of_keypoint[k] = static_cast<int>(w->points.size());
        TakePoint(earlier, i, &taken, w);
      }
      if (guided) TakeGuidedPoints(earlier, &taken, w);
    }
  }

  void TakePoint(const LinkResult& link, int i, std::unordered_set<long>* taken, FrameWork* w) {
    w->points.push_back(link.points[i]);
    w->ids.push_back(link.ids[i]);
    taken->insert(link.ids[i]);
    ++w->relinked;
  }

  // The link's guided-KLT tracks (those on no keypoint) whose point is not
  // within a pixel of a track the frame has (the same point, another id).
  void TakeGuidedPoints(const LinkResult& link, std::unordered_set<long>* taken, FrameWork* w) {
    std::vector<bool> on_keypoint(link.points.size(), false);
    for (int i : link.point_of_keypoint)
      if (i >= 0) on_keypoint[i] = true;
    cv::Mat occupied(w->size, CV_8U, cv::Scalar(0));
    const int radius = 1;
    for (const cv::Point2f& p : w->points) cv::circle(occupied, p, radius, cv::Scalar(255), cv::FILLED);
    for (size_t i = 0; i < link.points.size(); ++i) {
      const cv::Point2f& p = link.points[i];
      const cv::Point q(std::clamp(static_cast<int>(std::lround(p.x)), 0, w->size.width - 1),
                        std::clamp(static_cast<int>(std::lround(p.y)), 0, w->size.height - 1));
      if (on_keypoint[i] || taken->count(link.ids[i]) || occupied.at<unsigned char>(q)) continue;
      TakePoint(link, static_cast<int>(i), taken, w);
      cv::circle(occupied, p, radius, cv::Scalar(255), cv::FILLED);
    }
  }

  // Descriptor mode: the frame is linked to the last one by SIFT (else to
  // the last well-linked one). Stills: no link to either splits the shot.
  // KLT takes over once a link's motion is within its reach; in a video
  // also when no link is found (as after a KLT collapse: a blurred whip pan
  // defeats descriptors too; cuts in video are the shot detector's to find).
  void DescribedStep(const Frame& frame, const ShotDecision& decision, FrameTracks* out, FrameWork* w) {
    w->size = frame.gray.size();
    w->pyramid = std::move(spare_pyramid);  // KLT may take the next frame
    cv::buildOpticalFlowPyramid(FlatFieldedPicture(frame.gray, w), w->pyramid, Window(), options.pyramid_levels - 1,
                                true);
    if (options.match_fade_contrast) RememberContrast(frame.gray);
    w->had_tracks = !last_described.empty() || !good_described.empty();
    w->before = last_described.points.size();
    DescribedFrame cur;
    cur.gray = frame.gray;
    linker.Describe(&cur);
    LinkResult link;
    cv::Mat linked = last_described.gray;  // the view `link` links to
    if (!last_described.empty()) link = linker.Link(last_described, cur, &last_link);
    if (!link.ok() && !good_described.empty() && good_described.gray.data != last_described.gray.data) {
      link = linker.Link(good_described, cur);
      linked = good_described.gray;
    }
    last_link = link;
    RecordLink(frame, "stills", link, link.points.size());
    if (w->had_tracks && !link.ok() && Stills()) {
      StartShotAtThisFrame(out, &w->points, &w->ids);
      w->had_tracks = false;
      descriptor_mode = true;  // this frame is described; KLT (video) from the next
    } else if (link.ok()) {
      out->weak_link = Stills() && link.verified_matches < 2 * linker.options().min_verified;
      TakeLink(link, {}, w);
      out->recovered = w->relinked > 0;
      out->jump = link.median_motion_px >= options.klt_window;
      cur.point_of_keypoint = link.point_of_keypoint;
      if (decision.transition) {
        std::vector<float> disp;
        for (size_t i = 0; i < link.points.size(); ++i)
          disp.push_back(static_cast<float>(cv::norm(link.points[i] - link.key_points[i])));
        AccumulateRun(w->before, w->relinked, std::move(disp), frame.gray.cols);
      }
    }
    std::deque<DescribedFrame>* views = ViewsToLink(Stills(), out->jump);
    if (link.ok() && views) LinkEarlierViews(views, linked, &cur, w);
    if (Stills()) {
      if (cur.point_of_keypoint.empty()) cur.point_of_keypoint.assign(cur.keypoints.size(), -1);
      LinkEarlierShots(&cur, out, w);
    }
    DescribedTopUp(&cur, w);
    last_described = cur;
    if (views) KeepView(views, cur);
    if (Stills()) KeepStillsView(cur, frame.index);
    // Well linked: twice the matches a link needs (a shot's first frame too).
    if (!w->had_tracks || link.verified_matches >= 2 * linker.options().min_verified) good_described = cur;
    // Frames as close as a video's (a folder of a video's frames too): KLT,
    // far more precise than keypoints, takes the next frame; the probe
    // brings the descriptors back where it fails.
    if ((!Stills() && !link.ok()) || (link.ok() && link.median_motion_px < options.klt_window)) {
      descriptor_mode = false;
      stills_by_evidence = false;
    }
  }

  // The finished stills shot's first and last views, for the stills after
  // it to link to across the split.
  void KeepStillsShotEnds() {
    StillsShotEnds ends{{shot_first_stills.begin(), shot_first_stills.end()},
                        {shot_last_stills.rbegin(), shot_last_stills.rend()}};
    shot_first_stills.clear();
    shot_last_stills.clear();
    if (ends.first.empty()) return;
    earlier_stills_shots.push_back(std::move(ends));
    if (earlier_stills_shots.size() > kEarlierStillsShots) earlier_stills_shots.pop_front();
  }

  void KeepStillsView(const DescribedFrame& view, int index) {
    ShotView kept{view, shot, index};
    if (shot_first_stills.size() < kShotEndViews) {
      shot_first_stills.push_back(std::move(kept));
      return;
    }
    shot_last_stills.push_back(std::move(kept));
    if (shot_last_stills.size() > kShotEndViews) shot_last_stills.pop_front();
  }

  // Stills: links the still to the kept views of earlier stills shots; a
  // link the linker verifies (beyond chance, as every link) continues that
  // view's tracks here and is reported, so the estimator can place both
  // shots in one frame (a ring that came round to its start).
  void LinkEarlierShots(DescribedFrame* cur, FrameTracks* out, FrameWork* w) {
    std::unordered_set<long> taken(w->ids.begin(), w->ids.end());
    for (StillsShotEnds& ends : earlier_stills_shots) {
      // From each end inwards until a view does not link (those further
      // in share less): most unrelated shots cost one attempt per end.
      for (std::vector<ShotView>* views : {&ends.first, &ends.last})
        for (ShotView& kept : *views)
          if (!LinkEarlierShotView(kept, cur, out, &taken, w)) break;
    }
  }

  bool LinkEarlierShotView(const ShotView& kept, DescribedFrame* cur, FrameTracks* out,
                           std::unordered_set<long>* taken, FrameWork* w) {
    const LinkResult link = linker.Link(kept.view, *cur);
    if (!link.ok()) return false;
    out->earlier_shot_links.push_back({kept.shot, kept.index, link.verified_matches});
    for (size_t k = 0; k < link.point_of_keypoint.size(); ++k) {
      const int i = link.point_of_keypoint[k];
      if (i < 0 || cur->point_of_keypoint[k] >= 0 || taken->count(link.ids[i])) continue;
      cur->point_of_keypoint[k] = static_cast<int>(w->points.size());
      TakePoint(link, i, taken, w);
    }
    // A view KLT tracked (a video's first frame): its tracks are corners,
    // carried by the guided KLT.
    const auto& on_keypoint = kept.view.point_of_keypoint;
    if (std::none_of(on_keypoint.begin(), on_keypoint.end(), [](int i) { return i >= 0; }))
      TakeGuidedPoints(link, taken, w);
    return true;
  }

  // The views a described frame is linked back to and kept among: the
  // shot's stills when linked as stills, a video shot's views on a jump
  // (frames within KLT's reach add nothing KLT did not link), else none.
  std::deque<DescribedFrame>* ViewsToLink(bool as_stills, bool jump) {
    if (as_stills) return &stills_views;
    return jump ? &shot_views : nullptr;
  }

  void KeepView(std::deque<DescribedFrame>* views, const DescribedFrame& view) {
    views->push_back(view);
    if (views->size() > kStillsViewsBack) views->pop_front();
  }

  // A frame KLT tracked becomes a shot view (undescribed, its picture
  // copied: the pyramids' buffers are reused) once its tracks moved a KLT
  // window from the last view's, or kept under half of them: frames closer
  // than that see the same points, a later one sees new ones too.
  void KeepKltView(const Frame& frame, const FrameWork& w) {
    // Only a jump, found by descriptor linking, links back to these views.
    if (!options.descriptor_linking || descriptor_mode || Stills() || w.points.empty()) return;
    if (!shot_views.empty()) {
      const DescribedFrame& last = shot_views.back();
      std::unordered_map<long, cv::Point2f> at_view;
      for (size_t i = 0; i < last.ids.size(); ++i) at_view.emplace(last.ids[i], last.points[i]);
      std::vector<float> moved;
      for (size_t i = 0; i < w.ids.size(); ++i) {
        const auto it = at_view.find(w.ids[i]);
        if (it != at_view.end()) moved.push_back(static_cast<float>(cv::norm(w.points[i] - it->second)));
      }
      if (2 * moved.size() >= last.ids.size() && Quantile(std::move(moved), 0.5) < options.klt_window) return;
    }
    DescribedFrame view;
    view.gray = frame.gray.clone();
    view.points = w.points;
    view.ids = w.ids;
    KeepView(&shot_views, view);
  }

  // Revisit links (revisit_links). A KLT frame becomes a revisit view once
  // under kRevisitViewKept of the last view's tracks are still live here
  // (closer views see the same points). Before it is kept, it is linked to
  // the earlier views KLT no longer links it to (kRevisitShared), the
  // kRevisitTries whose layout thumbnails look most like its own first (an
  // orbit's views of the same side). A verified link (DescriptorLinker:
  // beyond chance, checked against the two-view model) continues that
  // view's tracks here by the guided KLT.
  void RevisitStep(const Frame& frame, FrameWork* w) {
    if (!options.revisit_links || descriptor_mode || Stills() || w->points.empty() ||
        shots.layout().empty())
      return;
    if (!revisit_views.empty() && !RevisitViewDue(revisit_views.back().view, *w)) return;
    const std::vector<size_t> candidates = RevisitCandidates(*w);
    if (!candidates.empty()) {
      DescribedFrame cur;
      cur.gray = frame.gray;
      linker.Describe(&cur);
      std::unordered_set<long> taken(w->ids.begin(), w->ids.end());
      for (size_t c : candidates) {
        DescribedFrame& view = revisit_views[c].view;
        if (view.keypoints.empty()) linker.Describe(&view);
        const LinkResult link = linker.Link(view, cur);
        const size_t before = w->relinked;
        if (link.ok()) TakeUntakenPoints(link, &taken, w);
        RecordLink(frame, "revisit", link, w->relinked - before);
      }
    }
    RevisitView kept{{}, shots.layout().clone()};
    kept.view.gray = frame.gray.clone();
    kept.view.points = w->points;
    kept.view.ids = w->ids;
    revisit_views.push_back(std::move(kept));
    if (revisit_views.size() > kRevisitViews) revisit_views.pop_front();
  }

  // Every point the link carries whose track is not in `taken`. A revisit
  // takes it also where a live track sits on the same corner (detected again
  // under a new id), since the earlier id is what ties this view to the
  // earlier turn; a bridge takes the anchor's tracks but for those the frame
  // has (its own tracks began in the break and tie it to nothing placed).
  void TakeUntakenPoints(const LinkResult& link, std::unordered_set<long>* taken, FrameWork* w) {
    for (size_t i = 0; i < link.points.size(); ++i)
      if (!taken->count(link.ids[i])) TakePoint(link, static_cast<int>(i), taken, w);
  }

  // Under kRevisitViewKept of `last`'s tracks live in this frame.
  bool RevisitViewDue(const DescribedFrame& last, const FrameWork& w) {
    const std::unordered_set<long> live(w.ids.begin(), w.ids.end());
    const size_t still = std::count_if(last.ids.begin(), last.ids.end(),
                                       [&](long id) { return live.count(id) > 0; });
    return still < kRevisitViewKept * last.ids.size();
  }

  // The revisit views worth linking to this frame (indices, the most alike
  // first, L1 distance of the layout thumbnails): those KLT no longer links.
  std::vector<size_t> RevisitCandidates(const FrameWork& w) const {
    if (revisit_views.size() < 2) return {};
    const cv::Mat& now = shots.layout();
    const auto distance = [&](const cv::Mat& layout) {
      return layout.size() == now.size() ? cv::norm(layout, now, cv::NORM_L1) : HUGE_VAL;
    };
    const std::unordered_set<long> live(w.ids.begin(), w.ids.end());
    std::vector<std::pair<double, size_t>> alike;
    for (size_t v = 0; v + 1 < revisit_views.size(); ++v) {
      const RevisitView& r = revisit_views[v];
      const auto shared = std::count_if(r.view.ids.begin(), r.view.ids.end(),
                                        [&](long id) { return live.count(id) > 0; });
      if (shared > kRevisitShared * r.view.ids.size()) continue;
      alike.emplace_back(distance(r.layout), v);
    }
    std::sort(alike.begin(), alike.end());
    std::vector<size_t> out;
    for (size_t i = 0; i < alike.size() && i < kRevisitTries; ++i) out.push_back(alike[i].second);
    return out;
  }

  // A break inside the shot: KLT lost the last frame's tracks and neither
  // the ORB re-links nor the SIFT probe linked this frame to it (the shot
  // detector saw no cut: the picture continues, blurred or covered).
  bool BrokeHere(const FrameTracks& out, const FrameWork& w) const {
    return options.bridge_breaks && options.descriptor_linking && !Stills() &&
           out.boundary == ShotBoundary::kNone && w.had_tracks &&
           w.before >= kMinTracksForCollapse && w.collapsed &&
           w.survived + w.relinked < kMinTracksForCollapse && !prev_pyramid.empty();
  }

  // Tracking broke inside the shot (BrokeHere): the frames after the break
  // are linked by SIFT to the last frame before it (as any link: verified
  // against the two-view geometry), until one links, which continues that
  // frame's tracks (the shot goes on across the break), or kBridgeSeconds
  // pass (the estimator then splits the shot where it broke). Frames in
  // between are flagged `bridging`. Costs nothing while tracking holds.
  void BridgeBreak(const Frame& frame, FrameTracks* out, FrameWork* w) {
    // (A new shot dropped the anchor with its tracks, DropTracks, unless its
    // cut may be a break.)
    if (break_anchor.empty() && BrokeHere(*out, *w)) StartBreak(frame);
    if (break_anchor.empty()) return;
    if (break_began) {  // links from the next frame on (the probe tried this one)
      out->bridging = true;
      return;
    }
    if (break_anchor.keypoints.empty()) linker.Describe(&break_anchor);
    DescribedFrame cur;
    cur.gray = frame.gray;
    linker.Describe(&cur);
    const LinkResult link = linker.Link(break_anchor, cur);
    ++break_tries;
    const size_t before = w->relinked;
    if (link.ok()) {
      std::unordered_set<long> taken(w->ids.begin(), w->ids.end());
      TakeUntakenPoints(link, &taken, w);
    }
    RecordLink(frame, "bridge", link, w->relinked - before);
    // A link carrying a few tracks (a blurred frame's handful of matches)
    // places nothing: the next frame may link better.
    if (w->relinked - before >= kMinTracksForCollapse) {
      out->recovered = true;
      out->jump = out->jump || link.median_motion_px >= options.klt_window;
      break_anchor = {};
      out->boundary = ShotBoundary::kNone;  // the same take: cuts seen since are withdrawn
      out->shot = shot = break_shot;
    } else if (frame.time_s - break_time_s > kBridgeSeconds || break_tries >= kBridgeTries) {
      break_anchor = {};  // gave up: the estimator splits where the shot broke
    } else {
      out->bridging = true;
    }
  }

  // The last frame (picture copied: the pyramids' buffers are reused, and
  // its tracks) becomes the anchor the next frames are linked back to.
  void StartBreak(const Frame& frame) {
    break_anchor = {};
    break_anchor.gray = prev_pyramid[0].clone();
    break_anchor.points = prev_points;
    break_anchor.ids = prev_ids;
    break_time_s = frame.time_s;
    break_tries = 0;
    break_shot = shot;
    break_began = true;
  }

  // The shot detector's cut (histogram) on a picture that continues the
  // last one (ShotDecision::continuity: the last picture shifted, at 64 px),
  // after a tracked frame: heavy blur (which flattens the histogram) or a
  // flash, not another picture (cuts measured at 0.24-0.64, docs/extract.md).
  // The tracks end as at any cut, but the bridge links the next frames back
  // to the last frame before it; one that links withdraws the cut.
  bool CutMayBeABreak(const ShotDecision& decision) const {
    if (!options.bridge_breaks || !options.descriptor_linking || Stills() ||
        decision.boundary != ShotBoundary::kCut || decision.continuity < kContinuousPicture)
      return false;
    return !break_anchor.empty() ||
           (prev_points.size() >= kMinTracksForCollapse && !prev_pyramid.empty());
  }

  FrameTracks Process(const Frame& frame) {
    if (frame.gray.empty() || frame.gray.type() != CV_8UC1)
      throw Error("frame " + std::to_string(frame.index), "tracker needs a CV_8UC1 gray image");
    FrameTracks out;
    out.index = frame.index;
    out.time_s = frame.time_s;
    // The index gap since the last frame: > 1 where the decoder skipped frames.
    out.step = prev_index >= 0 ? std::max(frame.index - prev_index, 1) : 1;
    prev_index = frame.index;
    const ShotDecision decision = shots.Update(frame);
    DecideBoundary(frame, decision, &out);
    if (decision.blank) {
      out.bridging = !break_anchor.empty() && out.boundary == ShotBoundary::kNone;
      EndTracksAtBlank();
      last_layout.release();
      return out;
    }
    after_blank = false;
    step = out.step;
    FrameWork w;
    if (descriptor_mode) {
      DescribedStep(frame, decision, &out, &w);
    } else {
      TrackFromLastFrame(frame, decision.transition, &w);
      Recover(frame, &out, &w);
      CheckCut(frame, decision, &out, &w);
      ProbeDescriptors(frame, &out, &w);
    }
    BridgeBreak(frame, &out, &w);
    const size_t verified = w.had_tracks ? w.survived + w.relinked : w.points.size();
    RevisitStep(frame, &w);
    TopUpIfThin(frame, &w);
    // Quality: verified (tracked or re-linked) share of the wanted tracks;
    // on a shot's first tracked frame nothing can be verified yet, so the
    // detections count.
    const size_t counted = w.had_tracks ? verified : w.points.size();
    out.quality = std::min(1.0, static_cast<double>(counted) / options.max_tracks);
    if (decision.transition) out.quality = std::min(out.quality, kTransitionQualityCap);
    // Keyframe for recovery: the last frame where tracking was healthy.
    const bool healthy = w.had_tracks ? (w.before > 0 && w.survived >= kGoodSurvival * w.before &&
                                         w.survived >= kMinTracksForCollapse)
                                      : w.points.size() >= kMinTracksForCollapse;
    if (healthy || (out.recovered && w.relinked >= kMinTracksForCollapse))
      relinker.SetKeyframe(frame.gray, w.points, w.ids);
    WriteTracks(frame, w, &out);
    KeepKltView(frame, w);
    out.still = Stills();
    ++shot_tracked_frames;
    UpdateAnchors(frame.index, w);
    KeepForNextFrame(&w);
    prev_tracked_index = frame.index;
    last_layout = shots.layout();
    return out;
  }
};

FeatureTracker::FeatureTracker(const TrackerOptions& options, Diagnostics* diagnostics) {
  options.Check();
  impl_ = std::make_unique<Impl>(options);
  impl_->diagnostics = diagnostics;
}

FeatureTracker::~FeatureTracker() = default;

FrameTracks FeatureTracker::Process(const Frame& frame) { return impl_->Process(frame); }

}  // namespace hapcine
