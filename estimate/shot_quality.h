#pragma once
// How far to trust each shot of an estimated camera path: a per-shot
// summary written in the path's header (`# shot_quality.<shot>=...`,
// docs/formats.md), in the --report file and as one warning line per
// doubtful shot by `hapcine estimate`.
//
// Doubtful (the rule, docs/estimate.md "Shot quality"): more than 5 % of
// the shot's frames lost (one frame in twenty has no pose), or a median
// confidence below 0.12, i.e. more than half its frames are weak. A frame
// whose tracks are all inliers with a small RMS gets 0.3 at the floor of
// track quality, 0.24 with the focal unobserved (what the synthetic suite's
// clean shots get: medians 0.21-0.91); below half of that, the inlier share
// times the RMS likelihood exp(-0.5 (rms / 2 px)^2) is under 1/2: half the
// tracks disagree with the pose, or the RMS exceeds 2.35 px (1.2 sigma of
// the confidence's noise model).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera_path.h"
#include "estimate/window/window_solver.h"

namespace hapcine {

struct ShotQuality {
  int shot = 0;
  int first_frame = 0, last_frame = 0;  // frame indices
  int frames = 0;                       // rows of the shot
  int lost = 0;                         // of them, model `lost`
  double median_confidence = 0;         // over all its frames (lost ones count 0)
  // From the shot's bundle-adjustment windows (none with --backend colmap):
  std::optional<double> inlier_ratio;      // two-view inliers / correspondences of its keyframes
  std::optional<double> rms_px;            // reprojection RMS, pixels at 960 px width
  std::optional<bool> focal_observable;    // some window turned enough to calibrate the focal
  // Frames written by windows whose zoom decision was ambiguous
  // (zoom_evidence.h: the evidence within half a threshold of the other
  // reading; the confidence lowered, the reading without zoom taken where it
  // is the simpler one); 0: no ambiguous decision, or none to make.
  std::optional<int> zoom_ambiguous;
  bool doubtful = false;
};

constexpr double kDoubtfulLostShare = 0.05;
constexpr double kDoubtfulMedianConfidence = 0.12;

// One entry per shot of `path`, in order. `width`: the decoded width.
std::vector<ShotQuality> SummariseShots(const CameraPath& path, const std::vector<WindowReport>& windows,
                                        int width);

// `# shot_quality.<shot>=first:F last:L frames:N lost:K median_confidence:C
// inlier_ratio:I rms_px:R focal_observable:0|1 zoom_ambiguous:Z doubtful:0|1`
// (I, R, focal, Z absent when unknown) into the path's metadata, and the
// reverse.
void WriteShotQuality(const std::vector<ShotQuality>& shots, CameraPath* path);
std::vector<ShotQuality> ReadShotQuality(const CameraPath& path);

nlohmann::json ShotQualityJson(const ShotQuality& q);
// "shot 2 (frames 120-260): doubtful: 14 frames lost, median confidence 0.21"
std::string DoubtfulShotLine(const ShotQuality& q);
// "shot 0 (frames 0-159): zoom ambiguous in 41 of 160 frames (zoom or dolly,
// zoom or none): confidence lowered"
std::string AmbiguousZoomLine(const ShotQuality& q);

}  // namespace hapcine
