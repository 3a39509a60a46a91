#include "datasets/eval_haptics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/csv.h"
#include "core/error.h"
#include "haptics/camera_signals.h"

namespace hapcine {

CameraPath ScaleEstimateToGroundTruth(const CameraPath& est, const EvalReport& r) {
  // Scale of each estimate frame: that of the shot its matched GT frame is in.
  std::map<int, double> shot_scale;
  for (const SegmentReport& s : r.shots) {
    if (s.shot) shot_scale[*s.shot] = s.align_scale;
  }
  std::map<int, double> frame_scale;  // est frame index -> scale
  for (const FrameError& e : r.per_frame) {
    const auto it = shot_scale.find(e.shot);
    frame_scale[e.est_frame] = it != shot_scale.end() ? it->second : r.overall.align_scale;
  }
  CameraPath out = est;
  double last = r.overall.align_scale;
  for (CameraFrame& f : out.frames) {
    const auto it = frame_scale.find(f.frame);
    if (it != frame_scale.end()) last = it->second;
    // Unmatched frames keep the scale of the previous matched one. A scale
    // that is not positive and finite (degenerate alignment) counts as 1.
    const double s = std::isfinite(last) && last > 0 ? last : 1.0;
    f.center *= s;
  }
  return out;
}

HapticEvalReport EvaluateHapticDifference(const CameraPath& gt, const CameraPath& est,
                                          const EvalReport& path_report,
                                          const HapticOptions& options) {
  return EvaluateHapticDifferenceToTrack(HapticTrack(), gt, est, path_report, options);
}

// `reference` empty: the ground truth path's track.
HapticEvalReport EvaluateHapticDifferenceToTrack(const HapticTrack& reference,
                                                 const CameraPath& gt, const CameraPath& est,
                                                 const EvalReport& path_report,
                                                 const HapticOptions& options) {
  HapticOptions o = options;
  if (o.source.empty()) o.source = path_report.gt_source;
  // Each path's problems name its own file (the tracks share the options).
  ValidatePathForHaptics(gt, path_report.gt_source.empty() ? "ground truth" : path_report.gt_source,
                         o.max_gap_s);
  ValidatePathForHaptics(est, path_report.est_source.empty() ? "estimate" : path_report.est_source,
                         o.max_gap_s);
  const CameraPath scaled = ScaleEstimateToGroundTruth(est, path_report);
  const auto [gt_track, b] = MakeComparableHapticTracks(gt, scaled, o);
  const HapticTrack& a = reference.samples.empty() ? gt_track : reference;
  HapticEvalReport r;
  r.model = b.model;
  r.rate_hz = b.rate_hz;
  r.difference = HapticTrackDifference(a, b);
  if (r.difference.num_samples == 0) {
    const std::string ref = reference.samples.empty() ? path_report.gt_source : reference.source;
    throw Error(ref + " vs " + path_report.est_source, "haptic tracks do not overlap in time");
  }
  for (const HapticSample& s : a.samples) {
    for (int k = 0; k < kNumActuators; ++k) {
      r.gt_peak_m[k] = std::max(r.gt_peak_m[k], s.pos_m[k].cwiseAbs().maxCoeff());
    }
  }
  r.est_clamped_samples = std::atoi(b.metadata.at("clamped_samples").c_str());
  return r;
}

nlohmann::json HapticEvalToJson(const HapticEvalReport& r) {
  nlohmann::json j;
  j["model"] = r.model;
  j["rate_hz"] = r.rate_hz;
  j["samples"] = r.difference.num_samples;
  j["est_clamped_samples"] = r.est_clamped_samples;
  for (int k = 0; k < kNumActuators; ++k) {
    j["actuators"][ActuatorName(static_cast<Actuator>(k))] = {
        {"rms_m", r.difference.rms_m[k]},
        {"max_m", r.difference.max_m[k]},
        {"gt_peak_m", r.gt_peak_m[k]}};
  }
  return j;
}

std::string FormatHapticEvalTable(const HapticEvalReport& r) {
  std::ostringstream out;
  out << "haptic difference (" << r.model << " model, same scaling for both, "
      << r.difference.num_samples << " samples at " << FormatDouble(r.rate_hz) << " Hz)\n";
  out << "  actuator   rms (mm)   max (mm)   GT peak (mm)\n";
  for (int k = 0; k < kNumActuators; ++k) {
    char line[128];
    std::snprintf(line, sizeof line, "  %-8s %9.2f %10.2f %14.2f\n",
                  ActuatorName(static_cast<Actuator>(k)), r.difference.rms_m[k] * 1e3,
                  r.difference.max_m[k] * 1e3, r.gt_peak_m[k] * 1e3);
    out << line;
  }
  if (r.est_clamped_samples > 0) {
    out << "  (estimate track: " << r.est_clamped_samples
        << " samples clamped to the workspace with the GT's scaling)\n";
  }
  return out.str();
}

}  // namespace hapcine
