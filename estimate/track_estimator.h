#pragma once
// Feature tracks in, camera path out — the streaming core of the estimator,
// independent of video decoding (tests feed synthetic FrameTracks).
//
// Per shot:
//  1. Keyframes: a frame becomes a keyframe when the median track motion
//     since the last keyframe exceeds `keyframe_motion`, when too few of its
//     tracks survive, or after `keyframe_max_gap` frames.
//  2. Each keyframe interval gets the simplest motion model that explains it
//     (GRIC, model_selection.h) and an initial relative pose from that model.
//     Isolated labels between two more general neighbours are promoted.
//  3. Every `window_frames` frames (and at the end of the shot) the window's
//     keyframes are bundle-adjusted (bundle_adjustment.h) with the parameter
//     sharing the models dictate; the window overlaps the previous one by two
//     keyframes, held constant, so memory is flat in video length.
//     General windows are solved twice, with constant and with per-keyframe
//     focal, and BIC decides "general" vs "general+zoom". Tracks whose
//     reprojection RMS exceeds `track_rms_cut_px` are dropped whole.
//  4. Frames between keyframes get a pose-only solve against the window's
//     points, with only the model's freedoms.
//  5. At the end of the shot: zero-phase smoothing per segment, conversion to
//     the file's OpenGL convention, units of median scene depth.

#include <array>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/geometry/model_selection.h"
#include "estimate/geometry/motion_hypotheses.h"
#include "estimate/geometry/motion_model.h"
#include "estimate/lens_bundle.h"
#include "estimate/window/loop_bundle.h"
#include "estimate/window/window_solver.h"
#include "extract/tracks.h"

namespace hapcine {

class Diagnostics;

// A placed frame's confidence (docs/estimate.md "Confidence"): the
// interval's two-view inlier ratio x the frame's track quality (at least
// 0.3) x the RMS likelihood exp(-0.5 (rms / 2 px)^2) (`rms_reference_px`:
// pixels at 960 px width) x 0.8 where the window's focal is not observable
// x the window's zoom-decision factor (ZoomConfidenceFactor,
// zoom_evidence.h) x 0.3 if its bundle adjustment failed.
double PlacedFrameConfidence(double inlier_ratio, double track_quality, double rms_reference_px,
                             const WindowOutcome& w);

struct TrackEstimatorOptions {
  double prior_hfov_deg = 50;        // focal prior (horizontal FOV) where focal is not observable
  int window_frames = 120;           // frames per bundle-adjustment window (long shots)
  int max_points = 300;              // points per window
  // Points spread over point_grid_cells^2 image cells (point_selection.h) in
  // translating windows (not along the optical axis); 0 or 1: longest first.
  int point_grid_cells = 6;
  // Those windows take max_points x this: the whole-track cut drops about
  // half of them on footage with silhouettes (occlusion-edge corners, and
  // good tracks the first bent solve puts far), and a window left with too
  // few rigid points bends along the rotation/translation ambiguity (a crane
  // move past a subject: 0.145 deg with x1, 0.020 with x2).
  double spread_points_factor = 2;
  double keyframe_motion = 0.02;     // median track motion for a new keyframe, fraction of width
  double keyframe_min_shared = 0.7;  // fraction of the last keyframe's tracks still alive
  int keyframe_max_gap = 6;          // frames; a keyframe at least this often
  int min_tracks = 12;               // fewer usable tracks: the frame holds the previous pose
  double min_rotation_for_focal_deg = 3;  // optical-axis turn needed to self-calibrate the focal
  bool smooth = true;                // zero-phase smoothing of the final path
  double smooth_sigma_frames = 1.5;  // Gaussian sigma of that smoothing, frames
  int ba_iterations = 40;            // Ceres iterations per window solve
  // A track whose reprojection RMS in the window's BA exceeds this (pixels at
  // 960 px width) is dropped whole (occlusion-edge tracks, slides).
  double track_rms_cut_px = 0.2;
  // The same in windows without translation, or where fewer than half the
  // keyframe intervals translate: without parallax an occlusion edge does not
  // slide and the RMS is tracking noise (blur of a whip pan, fades).
  double track_rms_cut_rotation_px = 0.4;
  // Window-level BIC tests of the two-view labels (window_freedoms.h): a few
  // translating (or, without translation, zooming) intervals keep their
  // freedoms only if they pay for themselves over the whole window (motion
  // blur or a fade reads as translation in a pair of frames, not in a
  // window); in a window with translation, intervals labelled as a zoom
  // become general if that pays (the slow start of a forward dolly reads as
  // a zoom in a pair of frames).
  bool freedom_test = true;
  // Those tests' noise grows with the image speed (motion blur,
  // window_freedoms.h BlurSigmas): sigma^2 + (this * px per frame)^2.
  double blur_noise_per_speed = 0.04;
  // A dolly with a zoom along the optical axis: the depths the images leave
  // open (axial_ambiguity.h) are those that put a sloped plane among the
  // points (the floor, a wall) parallel to the move (motion_plane.h).
  bool motion_plane_prior = true;
  // Observations weighted by their track's expected drift, which grows with
  // the frames followed (window/track_drift.h). Off: measured not to help
  // (docs/estimate.md, "Track drift weights").
  bool drift_weights = false;
  int num_threads = 1;               // Ceres threads
  // The first shot's first solved windows kept for the lens adjustment
  // (lens_bundle.h); 0: none is copied.
  int keep_solved_windows = 0;
  // After the last window of a translating shot: its keyframes adjusted
  // together where tracks close a loop no window saw whole (loop_bundle.h;
  // the tracker's revisit links make them). Off: the windows' path as is.
  bool loop_bundle = false;
  TwoViewOptions two_view;           // model selection
  // The camera's motion told from a large subject's (motion_hypotheses.h):
  // the frame's border, where the background is, decides.
  MoverOptions movers;
  void Check() const;                // throws UsageError
};

class TrackCameraEstimator {
 public:
  // width, height: decoded frame size (tracks are in its pixels).
  // `diagnostics`: where each window's report goes ("window" records,
  // core/diagnostics.h); none by default. Not owned; outlives the estimator.
  TrackCameraEstimator(int width, int height, const TrackEstimatorOptions& options,
                       Diagnostics* diagnostics = nullptr);
  // Frames in order. Emits finished frames into the path as windows close.
  void AddFrame(const FrameTracks& tracks);
  // Closes the last shot and returns every frame (metadata: width, height).
  CameraPath Finish();
  const std::vector<WindowReport>& reports() const { return reports_; }
  // The first shot's first windows as solved (cameras, kept points, their
  // observations), up to options.keep_solved_windows of them: what the lens
  // adjustment measures k1 on (lens_bundle.h).
  const std::vector<SolvedWindow>& solved_windows() const { return solved_windows_; }
  // No more window will be kept: as many as asked, or the first shot ended.
  bool solved_windows_complete() const;

 private:
  struct BufferedFrame {
    FrameTracks tracks;
    int video_pos = 0;  // shot-relative frame of the video (FrameTracks::step summed)
    KeyframeTracks u;   // normalised coordinates by track id
    bool usable = false;
  };
  struct Keyframe {
    int pos = 0;                     // shot-relative frame position
    int video_pos = 0;               // the same in frames of the video (BufferedFrame)
    BaCamera cam;                    // OpenCV world of the shot
    MotionModel model = MotionModel::kStatic;  // of the interval ending here
    MotionModel two_view_model = MotionModel::kStatic;  // the same as the two-view test read it
    double inlier_ratio = 1;
    bool fixed = false;              // pose constant in the window's BA
    bool fixed_focal = false;        // focal constant too (overlap with the previous window)
    bool chain_start = false;        // first keyframe of a chain: no interval of its own
    // The interval's model selection, for the report: matches, inliers, GRIC per candidate.
    int correspondences = 0, inliers = 0;
    std::array<double, kNumCandidates> gric{};
    // The share of the frame's edge cells holding the camera motion's inliers
    // (border_support.h); 1 for a still camera, which needs no confirmation.
    double border_support = 1;
    // Tracks at the border the interval's turn and zoom would move, and of
    // them those that stayed where they were (StillBorderTracks; none for a
    // still camera).
    StillBorder border_still;
  };
  struct RawPose {
    FrameTracks meta;                // index, time, shot, quality (points cleared)
    BaCamera cam;
    MotionModel model = MotionModel::kStatic;
    double confidence = 0;
    // Not placed from evidence (model `lost`, confidence 0): the pose is the
    // last placed one, a placeholder (docs/formats.md).
    bool lost = false;
  };

  void StartShot(int shot);
  void FinishShot();
  // Tracking broke inside a shot (fewer than min_tracks link the frame to
  // the last keyframe): the shot ends and a new one starts at `tracks`.
  void SplitShot(const FrameTracks& tracks);
  void RestartChain();
  // Tracking broke and the tracker is bridging (FrameTracks::bridging): the
  // frames are held until one is not, then lost if that one continues the
  // last keyframe's tracks, else added as they came (the shot splits).
  void AddFrameNow(const FrameTracks& tracks);
  void ResolveHeld(const FrameTracks* next);
  bool ContinuesLastKeyframe(const FrameTracks& tracks) const;
  bool EndsTheShot(const FrameTracks& tracks) const;
  bool SplitOfStills(const FrameTracks& tracks) const;
  void BorrowStillsFocal();
  void KeepStillsFocal();
  void SmoothShot(std::vector<Eigen::Quaterniond>* q, std::vector<Eigen::Vector3d>* c,
                  std::vector<double>* lf) const;
  void HoldPlaceholders(std::vector<Eigen::Quaterniond>* q, std::vector<Eigen::Vector3d>* c,
                        std::vector<double>* lf) const;
  RawPose LostPose(const FrameTracks& meta, const BaCamera& placeholder) const;
  // The shot's motion rests on a subject while its border stays still
  // (BorderStaysStill): every placed frame takes the shot's origin.
  bool BorderStaysStill() const;
  void HoldStillBeforeMover();
  void AddKeyframe(int pos, bool first);  // first: the chain's start (the shot's origin)
  int SharedWithLastKeyframe(const KeyframeTracks& u) const;
  Keyframe ChainStart(int pos) const;  // held, no interval of its own; camera left to the caller
  Keyframe LinkedKeyframe(const Keyframe& a, int pos);
  // The current window through SolveWindow (window_solver.h), then its
  // frames (track_estimator_window.cc). `final`: the shot ends with it.
  void ProcessWindow(bool final);
  WindowInput WindowInputOf(bool labels_revised) const;
  // The keyframes' cameras and labels as a window solve left them.
  void UpdateKeyframes(const std::vector<BaCamera>& cams, const std::vector<MotionModel>& labels);
  void Report(WindowReport report);
  void KeepSolvedWindow(const WindowOutcome& w);
  // The loop bundle (loop_bundle.h): the window's keyframes as solved, then
  // at the shot's end the adjustment and its correction of every frame.
  void KeepLoopKeyframes();
  void AdjustShotLoop();
  void CorrectRawPoses(const std::vector<int>& raw_of_keyframe,
                       const std::vector<BaCamera>& adjusted);
  // After the window's solve (track_estimator_frames.cc).
  void SetUnits(std::vector<BaPoint>* points);
  void EmitWindowFrames(const WindowOutcome& solution, bool final);
  void StartNextWindow();
  const BufferedFrame& At(int pos) const { return frames_[pos - buffer_start_]; }
  Eigen::Vector2d Normalise(const Eigen::Vector2d& px) const;

  int width_, height_;
  TrackEstimatorOptions options_;
  WindowOptions window_options_;
  Diagnostics* diagnostics_;
  double prior_log_focal_;
  CameraPath path_;
  std::vector<WindowReport> reports_;
  std::vector<SolvedWindow> solved_windows_;
  int solved_windows_shot_ = -1;     // the shot they are of

  // Current shot.
  int shot_ = -1;
  int source_shot_ = -1;             // the tracker's shot index of the current shot
  // Frames held while the tracker bridges a break (FrameTracks::bridging),
  // and whether they are being added as they came (the break not bridged).
  std::vector<FrameTracks> held_;
  bool replaying_held_ = false;
  // After a split: the focal the new shot starts from, and whether it was observed.
  std::optional<double> split_log_focal_;
  std::optional<double> last_log_focal_;  // the last placed frame's, set by FinishShot
  // The focal the stills footage's last calibrated shot reached (shots of
  // stills split where no view links; reset at a cut).
  std::optional<double> stills_log_focal_;
  int shot_frames_ = 0;              // frames seen in the shot
  int shot_video_frames_ = 0;        // the same in frames of the video (skipped ones too)
  bool shot_of_stills_ = false;      // a frame of the shot was linked as a still: no smoothing
  std::deque<BufferedFrame> frames_; // from buffer_start_ on
  int buffer_start_ = 0;
  std::vector<Keyframe> keyframes_;  // of the current window
  std::vector<RawPose> raw_;         // emitted raw poses of the shot
  std::vector<LoopKeyframe> loop_keyframes_;  // the shot's keyframes as solved (loop_bundle)
  int shot_windows_ = 0;                      // windows solved in the shot
  std::set<long> outlier_tracks_;
  // Per track, the window's intervals in which it moved on its own (the
  // border's motion was the camera's and not its) and in which it followed
  // the camera: it is kept out of the window's points when the first
  // outnumber the second (a near track read as a mover once, at the slow
  // start of a traveling, stays in).
  std::map<long, std::pair<int, int>> mover_intervals_;
  std::vector<double> focal_samples_;  // log f from rotation pairs with enough turn
  bool focal_observed_ = false;
  bool scale_set_ = false;
  double scene_depth_ = 1;
};

}  // namespace hapcine
