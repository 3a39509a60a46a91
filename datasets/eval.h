#pragma once
// Compare an estimated camera path against ground truth (docs/eval.md has the
// formulas). The metrics follow evo (github.com/MichaelGrupp/evo) where evo has
// one: ATE = evo_ape's translation part after Umeyama alignment, RPE = evo_rpe
// with a delta in frames. Camera-specific extras: rotation error relative to
// the first frame, horizontal FOV error, zoom-ratio error, spurious translation.
//
// Frames are matched by frame index; when fewer than half of the shorter
// path's frames share an index, by nearest time_s within half a frame period.
// Frames the estimate marks `lost` are not compared (their pose is a
// placeholder): they are counted per segment (lost_frames) and reported.
// When a `shot` column exists every shot is evaluated on its own, aligned on
// its own first frame (the estimator restarts each shot at the origin with its
// own scale), and the overall figures pool the per-shot errors.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "datasets/shot_boundaries.h"

namespace hapcine {

enum class TrajectoryAlignment { kSim3, kSe3, kNone };
enum class FrameMatching { kAuto, kFrameIndex, kTime };

const char* TrajectoryAlignmentName(TrajectoryAlignment a);  // "sim3", "se3", "none"
TrajectoryAlignment ParseTrajectoryAlignment(const std::string& name);  // throws UsageError
const char* FrameMatchingName(FrameMatching m);  // "auto", "frame", "time"
FrameMatching ParseFrameMatching(const std::string& name);  // throws UsageError

struct EvalOptions {
  // Alignment of the camera centres before ATE/RPE translation: sim3 (evo -as,
  // the right choice for monocular estimates of unknown scale), se3 (evo -a), none.
  TrajectoryAlignment align = TrajectoryAlignment::kSim3;
  // RPE frame distance (evo --delta with --delta_unit f).
  int rpe_delta = 1;
  FrameMatching matching = FrameMatching::kAuto;
  // Evaluate shots separately when a `shot` column exists (ground truth's if
  // it has one, else the estimate's).
  bool per_shot = true;
  // A ground-truth path shorter than this (in GT units) is "not moving": ATE %
  // is reported as n/a and the estimate's path length is the spurious
  // translation figure.
  double static_path_length = 1e-6;
  // An estimated shot boundary within this many frames of a ground-truth one
  // is found (shot_boundaries below).
  int shot_tolerance_frames = 2;
  void Check() const;  // throws UsageError
};

// count, mean, median, max, RMSE of non-negative per-frame errors.
struct ErrorStats {
  int count = 0;
  double mean = 0;
  double median = 0;
  double max = 0;
  double rmse = 0;
};
ErrorStats ComputeErrorStats(std::vector<double> values);

// Errors of one matched frame. Relative quantities (rotation, zoom ratio) are
// relative to the first matched frame of the frame's shot.
struct FrameError {
  int gt_frame = 0;
  int est_frame = 0;
  double time_s = 0;          // ground truth's
  int shot = 0;               // 0 when there is no shot column
  double rotation_deg = 0;    // angle((R_gt0^-1 R_gt)^-1 (R_est0^-1 R_est))
  double fov_deg = 0;         // |fov_est - fov_gt|
  double fov_percent = 0;     // 100 |fov_est - fov_gt| / fov_gt
  double zoom_ratio_percent = 0;  // 100 |(f_est/f_est0) / (f_gt/f_gt0) - 1|
  double ate = 0;             // |c_gt - align(c_est)|, GT units
  // RPE of the pair (this frame, delta frames later) when that frame exists.
  std::optional<double> rpe_rotation_deg;
  std::optional<double> rpe_translation;
};

struct SegmentReport {
  std::optional<int> shot;     // unset for the whole clip
  int frames = 0;              // matched frames in the segment (lost ones excluded)
  // Matched frames whose estimate is `lost` (docs/formats.md): left out of
  // every error statistic, and not counted as correct either.
  int lost_frames = 0;
  ErrorStats rotation_deg;
  ErrorStats fov_deg;
  ErrorStats fov_percent;
  ErrorStats zoom_ratio_percent;
  ErrorStats ate;              // GT units
  std::optional<double> ate_percent;  // RMSE as % of GT path length; n/a when GT is static
  double gt_path_length = 0;   // sum |c_{i+1} - c_i| over matched frames, GT units
  double est_path_length = 0;  // same for the estimate, estimate units, unaligned
  bool gt_static = false;      // gt_path_length < static_path_length
  double align_scale = 1;      // Sim(3) scale estimate units -> GT units (segment)
  ErrorStats rpe_rotation_deg;
  ErrorStats rpe_translation;  // GT units, after scale alignment
  std::optional<double> model_agreement;  // fraction of frames with equal `model`
  int model_frames = 0;        // frames where both paths have a model
};

struct EvalReport {
  std::string gt_source;
  std::string est_source;
  EvalOptions options;
  FrameMatching matching_used = FrameMatching::kFrameIndex;
  int gt_frames = 0;
  int est_frames = 0;
  int matched = 0;
  int unmatched_gt = 0;
  int unmatched_est = 0;
  SegmentReport overall;              // pooled over shots
  std::vector<SegmentReport> shots;   // empty without a shot column
  // Precision/recall of the estimate's shot boundaries; only when both paths
  // have a `shot` column.
  std::optional<ShotBoundaryScore> shot_boundaries;
  std::vector<FrameError> per_frame;  // matched frames, GT order
};

// Throws hapcine::Error when no frames match (naming both sources).
EvalReport EvaluateCameraPaths(const CameraPath& gt, const CameraPath& est,
                               const EvalOptions& options);

// Human-readable, column-aligned table.
std::string FormatEvalTable(const EvalReport& report);
// JSON (n/a values are null).
nlohmann::json EvalReportToJson(const EvalReport& report);
// Per-frame errors as CSV (header row; empty fields where RPE is undefined). Atomic.
void WritePerFrameErrorsFile(const EvalReport& report, const std::string& file);

}  // namespace hapcine
