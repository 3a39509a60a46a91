#pragma once
// `hapcine eval --haptic`: how different would the HapSeat feel with the
// estimated camera path instead of the ground truth?
//
// Both paths become haptic tracks with the SAME model and the SAME cinematic
// scaling (computed from the ground truth, the paper's pre-processing pass),
// so the difference measures the camera paths, not two normalisations. A
// monocular estimate has no metric scale: before its track is made, its
// camera centres are multiplied, shot by shot, by the Sim(3) scale that
// EvaluateCameraPaths found for that shot (estimate units -> GT units), so a
// path that is only off in scale is not penalised. The difference is
// |a(t) - b(t)| per actuator over the ground-truth track's samples inside
// the estimate's time range (haptics/haptic_models.h, HapticTrackDifference).

#include <nlohmann/json.hpp>
#include <string>

#include "core/camera_path.h"
#include "datasets/eval.h"
#include "haptics/haptic_models.h"

namespace hapcine {

struct HapticEvalReport {
  std::string model;                  // cinematic, semantic, random, none
  double rate_hz = 0;                 // of both tracks
  HapticDifference difference;        // ground truth track vs estimate track
  double gt_peak_m[kNumActuators] = {0, 0, 0};  // largest |coordinate| of the GT track
  int est_clamped_samples = 0;        // estimate track samples the final clamp touched
};

// `path_report` is EvaluateCameraPaths(gt, est, ...) (for the per-shot scale).
// Throws hapcine::Error when the tracks do not overlap in time.
HapticEvalReport EvaluateHapticDifference(const CameraPath& gt, const CameraPath& est,
                                          const EvalReport& path_report,
                                          const HapticOptions& options);

// The same, but the estimate's track is compared with `reference` (a track
// authored elsewhere: *.haptic.csv or .hjif) instead of the ground truth
// path's track; the scaling still comes from the ground truth path.
HapticEvalReport EvaluateHapticDifferenceToTrack(const HapticTrack& reference,
                                                 const CameraPath& gt, const CameraPath& est,
                                                 const EvalReport& path_report,
                                                 const HapticOptions& options);

// The estimate with its centres in ground-truth units (per-shot Sim(3) scale).
CameraPath ScaleEstimateToGroundTruth(const CameraPath& est, const EvalReport& path_report);

nlohmann::json HapticEvalToJson(const HapticEvalReport& report);
std::string FormatHapticEvalTable(const HapticEvalReport& report);

}  // namespace hapcine
