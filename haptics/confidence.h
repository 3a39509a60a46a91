#pragma once
// The camera path's `confidence` column in the cinematic model: a shaky,
// low-confidence estimate must not drive the seat at full range.
//
// Gain curve (ConfidenceGain): g(c) = SmootherStep(c / kFullGainConfidence),
// kFullGainConfidence = 0.24: 0 for a lost frame (c = 0), 1/2 at 0.12 (the
// estimator's "doubtful" median), 1 from 0.24 up (what the estimator gives a
// frame whose tracks are all inliers with a small reprojection error at the
// floor of track quality with the focal unobserved: docs/estimate.md
// "Confidence"); C2, so the gain never jumps. The confidence is first
// averaged over kConfidenceWindowS around each frame, so one noisy frame does
// not pump the gain. Frames without a confidence (ground truth) have gain 1.
//
// The gain scales the camera signals' frame-to-frame changes, not their
// values: a low-confidence span is felt weakly and a change of gain alone
// moves nothing. The per-shot scaling runs on these signals, so a
// low-confidence span hardly sets a shot's scale; and a shot whose frames
// are mostly of low confidence is scaled down by its median gain
// (ShotQualityGain), so scaling cannot blow its weak motion back up.

#include <string>
#include <vector>

#include "core/camera_path.h"
#include "haptics/camera_signals.h"

namespace hapcine {

constexpr double kFullGainConfidence = 0.24;
constexpr double kConfidenceWindowS = 0.5;
// The estimator's rule for a doubtful shot (docs/estimate.md "Shot quality").
constexpr double kLowMedianConfidence = 0.12;
constexpr double kLowLostShare = 0.05;

double ConfidenceGain(double confidence);

// Per frame of the shot: the confidence gain of the confidence averaged over
// kConfidenceWindowS (lost frames count 0; frames without one count 1).
std::vector<double> FrameConfidenceGains(const CameraPath& path, const ShotRange& shot);

// x_n = x_{n-1} + g_n (x_n - x_{n-1}) on every signal of the shot.
void ApplyConfidenceGain(const std::vector<double>& gains, CameraSignals* s);

// The factor a shot's scaling is multiplied by: the median of its frame
// gains, and at most the gain of the doubtful median confidence (1/2) where
// the estimator flagged the shot doubtful: its lost frames or the lack of
// any background confirming its motion (border support) make its motion no
// more trustworthy than a shot at that confidence.
double ShotQualityGain(const std::vector<double>& gains, bool doubtful);

// ShotQualityGain of every shot, doubtful as the path's header says.
std::vector<double> ShotQualityGains(const CameraPath& path, const std::vector<ShotRange>& shots);

struct ShotConfidence {
  int shot = 0;
  double start_s = 0, end_s = 0;
  size_t frames = 0, lost = 0;
  double median_confidence = 1;  // 1 when the path has no confidence
  double gain = 1;               // ShotQualityGain
  bool header_doubtful = false;  // the estimator's `shot_quality.<shot>` says doubtful:1
  // Low quality: doubtful in the header, more than 5 % lost, or a median
  // confidence below 0.12.
  bool low = false;
};
std::vector<ShotConfidence> AssessShotConfidence(const CameraPath& path,
                                                 const std::vector<ShotRange>& shots);

// "shot 3 (12.00-19.50 s): low quality (median confidence 0.08, 12 of 180
// frames lost, doubtful in the camera path): haptic gain 0.35"
std::string LowQualityShotLine(const ShotConfidence& c);

}  // namespace hapcine
