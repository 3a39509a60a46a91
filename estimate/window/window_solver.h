#pragma once
// One bundle-adjustment window of a shot, solved as a function: the
// keyframes with their two-view labels and tracks in, the solved keyframes,
// points and labels out (docs/estimate.md "Algorithm", step 4). The stream,
// shot and keyframe state around it is TrackCameraEstimator's
// (track_estimator.h), which also places the frames between the keyframes.
//
// The steps, each a function below that can be tested alone:
//  1. SetUpWindow: isolated labels promoted (PromoteShortRuns), the focal
//     initialised from rotation pairs that turned enough, the points chosen
//     and the solve options set.
//  2. The constant-focal solve; beside it, on other threads, the solve
//     without the few translating/zooming intervals' freedoms (FreedomTest-
//     Labels) and, in general windows, the per-keyframe-focal one.
//  3. Label tests (window_freedoms.h): freedoms that do not pay for
//     themselves are dropped, zoom intervals among translating ones promoted
//     to general if that pays; either returns revised labels, and the caller
//     solves the window again with them (once).
//  4. Focal and branch choice (ChooseWindowFocal): BIC between the constant
//     focal and the per-keyframe candidates; along the optical axis the
//     occlusion order or a floor rules out the wrong branch.
//  5. Whole-track rejection (DropBadTracks), then the plane prior of an axial
//     dolly/zoom (plane_prior.h).

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/geometry/border_support.h"
#include "estimate/geometry/motion_model.h"
#include "estimate/geometry/reference_width.h"
#include "estimate/window/window_points.h"
#include "estimate/window/zoom_evidence.h"

namespace hapcine {

class Diagnostics;

struct WindowKeyframe {
  int pos = 0;                     // shot-relative frame position
  BaCamera cam;                    // OpenCV world of the shot
  MotionModel model = MotionModel::kStatic;  // label of the interval ending here
  bool fixed = false;              // pose held (the lead-in from the previous window)
  bool fixed_focal = false;        // focal held too
  bool chain_start = false;        // first keyframe of a chain: no interval of its own
  const KeyframeTracks* tracks = nullptr;  // its tracks, normalised coordinates
  bool jump = false;               // reached by a jump (FrameTracks::jump): placed by resection where it can be
};

struct WindowInput {
  std::vector<WindowKeyframe> keyframes;
  // Every frame from the first keyframe to the last, in order (the
  // occlusion events: a track ends between keyframes).
  std::vector<const KeyframeTracks*> frames;
  std::set<long> outlier_tracks;   // two-view outliers: never the window's points
  int shot = 0, first_frame = 0;   // for the report
  int width = 1, height = 1;       // decoded frame size
  double prior_log_focal = 0;      // normalised focal prior, log
  bool focal_observed = false;     // an earlier window of the shot calibrated the focal
  std::vector<double> focal_samples;  // log f of rotation pairs that turned enough
  bool frames_written = false;     // the shot has frames before this window
  double scene_depth = 1;          // the median depth the shot's scale is in
  bool labels_revised = false;     // a second solve with revised labels: the label tests do not run again
  bool stills = false;             // a shot of stills (FrameTracks::still): keyframes whole steps apart
};

struct WindowOptions {
  int max_points = 300;            // points per window
  int point_grid_cells = 6;        // points spread over N x N cells in translating windows
  double spread_points_factor = 2; // those windows take max_points x this
  double min_rotation_for_focal_deg = 3;
  int ba_iterations = 40;
  double track_rms_cut_px = 0.2;           // whole-track cut, px at 960 px width
  double track_rms_cut_rotation_px = 0.4;  // the same where few intervals translate
  bool freedom_test = true;
  double blur_noise_per_speed = 0.04;
  bool motion_plane_prior = true;
  bool drift_weights = false;      // weight observations by their track's drift (track_drift.h)
  double noise_floor = 0.25 / kReferenceWidthPx; // normalised units
  int num_threads = 1;
};

// One reconstruction a window test compared. `score`: the test's criterion,
// lower wins: capped chi2 in units of sigma^2, plus the BIC penalty for the
// candidate with more freedoms.
struct WindowCandidate {
  std::string test;    // "freedoms", "promotion" or "focal"
  std::string name;    // e.g. "with", "without"; "current", "promoted"; "constant_focal", "per_keyframe_focal", "mirrored_branch"
  bool solved = false; // its bundle adjustment succeeded
  double score = 0;
  bool chosen = false;
  bool ruled_out = false;       // the occlusion order or the floor contradicts it (focal)
  int occlusion_agree = -1, occlusion_disagree = -1;  // votes (-1: not counted)
  int plane_support = -1;       // points on a plane parallel to the move (-1: not counted)
  double focal_first_px = 0, focal_last_px = 0;  // its first and last keyframe's focal (focal; 0: not recorded)
  double depth_relief = -1;     // the dolly's depth relief (dolly_or_zoom.h; -1: not measured)
  BaSummary ba;
};

// Per-window diagnostics, for the --report file (docs/formats.md) and tests.
struct WindowReport {
  int shot = 0;
  int first_frame = 0, last_frame = 0;
  int keyframes = 0, points = 0, observations = 0;
  double rms_px = 0;                 // after BA, pixels of the decoded frame
  bool focal_observable = false;
  bool zoom_by_bic = false;          // general segments were upgraded to general+zoom
  bool labels_revised = false;       // re-run with the labels the window-level tests revised (window_freedoms.h)
  bool plane_prior = false;          // depths shifted to put a floor or wall parallel to an axial move (plane_prior.h)
  bool branch_by_occlusion = false;  // the occlusion order ruled out a dolly/zoom branch
  double chain_focal_shift = 0;      // the two-view chain rebuilt at the focal x exp(this) (focal_search.h)
  std::string model = "constant_focal";  // the candidate taken
  std::vector<MotionModel> labels;   // the keyframe intervals' models after the solve
  std::vector<WindowCandidate> candidates;
  BaSummary ba;                      // of the solution taken, after every polish
  int points_kept = 0;               // points whose track survived the whole-track cut
  // Two-view inliers and correspondences of the window's free keyframes
  // (set by the estimator; the shot quality summary, shot_quality.h).
  int inliers = 0, correspondences = 0;
  // The same keyframes' border support (border_support.h; 1 where the
  // camera is still), in order.
  std::vector<double> border_support;
  // And their still border (StillBorderTracks), in the same order.
  std::vector<StillBorder> border_still;
  // Set on a shot's last window when the shot was read as a still camera
  // before a moving subject (StillBorderAroundMotion): every frame of the
  // shot was held at its first pose.
  bool shot_held_still = false;
  // Every zoom decision the window's tests made, with its evidence
  // (zoom_evidence.h; the first solve's too when the labels were revised).
  std::vector<ZoomDecision> zoom_decisions;
  std::vector<std::pair<std::string, double>> timings_s;  // wall seconds per step
};

struct WindowOutcome {
  // Set when the label tests revised the window's labels: solve it again
  // with these (WindowInput::labels_revised); only `keyframe_cams` is set besides.
  std::vector<MotionModel> revised_labels;
  // The keyframes' cameras: the focal initialised and, on success, solved.
  std::vector<BaCamera> keyframe_cams;
  std::vector<MotionModel> labels;   // the keyframes' models after the solve
  bool success = false;              // the bundle adjustment succeeded
  bool translating = false;          // some interval translates (points have depths)
  bool focal_observable = false;
  bool focal_calibrated = false;     // the shot's focal is calibrated from here on
  // The shot's focal calibrated for the first time: add this to the log
  // focal of the frames already written (they were estimated at the prior).
  std::optional<double> written_log_focal_shift;
  // What the frames between the keyframes are solved against.
  std::vector<BaPoint> points;
  std::map<long, int> point_of_track;  // track id -> index in points
  std::vector<char> point_kept;        // the BA kept the point's track
  BaOptions pose_options;
  double rms_px = 0;                   // pixels of the decoded frame
  WindowReport report;
};

WindowOutcome SolveWindow(const WindowInput& input, const WindowOptions& options, Diagnostics* diagnostics);

// --- The steps, exposed for tests.

// Labels of short runs (one or two intervals) between two equal, more
// general neighbours take theirs (an interval or two misread).
std::vector<MotionModel> PromoteShortRuns(const std::vector<WindowKeyframe>& keyframes);

// The shift of every keyframe's log focal that starts the window at the
// median of the focal samples (rotation pairs that turned enough), or none:
// only while the shot's focal is not calibrated, at the shot's first window
// or when `recalibrate_lead_in`.
std::optional<double> InitialFocalShift(const WindowInput& input, bool recalibrate_lead_in);

// The window's cameras from the keyframes, with the blocks each interval's
// model shares with the previous keyframe. `labels`: models to use instead
// of the keyframes' own; `zoom_in_general`: general intervals get a zoom;
// `free_lead_in_focal`: the held lead-in's focal is solved.
std::vector<BaCamera> WindowCameras(const std::vector<WindowKeyframe>& keyframes, bool zoom_in_general,
                                    bool free_lead_in_focal, const std::vector<MotionModel>* labels = nullptr);

// Which freedoms the freedom test drops (window_freedoms.h): the
// translation of every free interval in a window where few frames
// translate, the zoom where few zoom (without translation: only then).
// `any` false: no test.
struct FreedomTestPlan {
  bool any = false;
  std::vector<char> drop_translation, drop_zoom;
  std::vector<MotionModel> labels;  // the reduced labels
};
FreedomTestPlan FreedomTestLabels(const std::vector<WindowKeyframe>& keyframes);

// Free zoom intervals without translation, as general (the promotion test's
// labels); `promoted`: how many.
std::vector<MotionModel> PromotionLabels(const std::vector<WindowKeyframe>& keyframes, int* promoted);

// Whole-track rejection on a solved window: tracks whose RMS over `all`
// exceeds the cut (px at 960 px width) are dropped and the window polished
// (robust_bundle.h). `kept`: the observations left.
void DropBadTracks(const BaOptions& ba, double cut_px, std::vector<BaCamera>* cams, std::vector<BaPoint>* points,
                   const std::vector<BaObservation>& all, std::vector<BaObservation>* kept, BaSummary* summary);

}  // namespace hapcine
