#include "estimate/shot_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "core/csv.h"
#include "core/statistics.h"
#include "estimate/geometry/reference_width.h"

namespace hapcine {
namespace {

std::string Fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// The windows' figures per shot: inliers and correspondences summed, the
// RMS pooled over observations.
struct WindowTally {
  long inliers = 0, correspondences = 0;
  double sum_sq_px = 0;
  long observations = 0;
  bool focal_observable = false;
};

// The frame's confidence as its file states it (a float held value, read as
// the double of its shortest text: 0.3, not 0.30000001192092896).
double ConfidenceAsWritten(const CameraFrame& f) {
  if (!f.confidence) return 1.0;
  return std::strtod(FormatFloat((*f.confidence).raw()).c_str(), nullptr);
}

// Frames of shot `q` written by windows with an ambiguous zoom decision: each
// window writes the frames after the previous window's last, up to its own.
int ZoomAmbiguousFrames(const ShotQuality& q, const std::vector<WindowReport>& windows) {
  int frames = 0, written_up_to = q.first_frame - 1;
  for (const WindowReport& w : windows) {
    if (w.shot != q.shot) continue;
    const int first = std::max(written_up_to + 1, q.first_frame), last = std::min(w.last_frame, q.last_frame);
    if (WindowZoomAmbiguous(w.zoom_decisions) && last >= first) frames += last - first + 1;
    written_up_to = std::max(written_up_to, w.last_frame);
  }
  return frames;
}

}  // namespace

std::vector<ShotQuality> SummariseShots(const CameraPath& path, const std::vector<WindowReport>& windows,
                                        int width) {
  std::map<int, WindowTally> tally;
  for (const WindowReport& w : windows) {
    WindowTally& t = tally[w.shot];
    t.inliers += w.inliers;
    t.correspondences += w.correspondences;
    t.sum_sq_px += w.rms_px * w.rms_px * w.observations;
    t.observations += w.observations;
    t.focal_observable |= w.focal_observable;
  }
  std::vector<ShotQuality> out;
  std::vector<double> confidence;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    const CameraFrame& f = path.frames[i];
    const int shot = f.shot.value_or(0);
    if (out.empty() || out.back().shot != shot) {
      if (!out.empty()) out.back().median_confidence = Median(confidence);
      confidence.clear();
      out.push_back({});
      out.back().shot = shot;
      out.back().first_frame = f.frame;
    }
    ShotQuality& q = out.back();
    q.last_frame = f.frame;
    ++q.frames;
    q.lost += IsLost(f);
    confidence.push_back(IsLost(f) ? 0.0 : ConfidenceAsWritten(f));
  }
  if (!out.empty()) out.back().median_confidence = Median(confidence);
  for (ShotQuality& q : out) {
    if (auto it = tally.find(q.shot); it != tally.end()) {
      const WindowTally& t = it->second;
      if (t.correspondences > 0) q.inlier_ratio = static_cast<double>(t.inliers) / t.correspondences;
      if (t.observations > 0 && width > 0)
        q.rms_px = std::sqrt(t.sum_sq_px / t.observations) * kReferenceWidthPx / width;
      q.focal_observable = t.focal_observable;
      q.zoom_ambiguous = ZoomAmbiguousFrames(q, windows);
    }
    q.doubtful = q.lost > kDoubtfulLostShare * q.frames || q.median_confidence < kDoubtfulMedianConfidence;
  }
  return out;
}

nlohmann::json ShotQualityJson(const ShotQuality& q) {
  auto opt = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"shot", q.shot},
          {"first_frame", q.first_frame},
          {"last_frame", q.last_frame},
          {"frames", q.frames},
          {"lost", q.lost},
          {"median_confidence", q.median_confidence},
          {"inlier_ratio", opt(q.inlier_ratio)},
          {"rms_px", opt(q.rms_px)},
          {"focal_observable", opt(q.focal_observable)},
          {"zoom_ambiguous", opt(q.zoom_ambiguous)},
          {"doubtful", q.doubtful}};
}

std::string DoubtfulShotLine(const ShotQuality& q) {
  std::string s = "shot " + std::to_string(q.shot) + " (frames " + std::to_string(q.first_frame) + "-" +
                  std::to_string(q.last_frame) + "): doubtful: ";
  if (q.lost > 0) s += std::to_string(q.lost) + " of " + std::to_string(q.frames) + " frames lost, ";
  return s + "median confidence " + Fixed(q.median_confidence, 2);
}

std::string AmbiguousZoomLine(const ShotQuality& q) {
  return "shot " + std::to_string(q.shot) + " (frames " + std::to_string(q.first_frame) + "-" +
         std::to_string(q.last_frame) + "): zoom ambiguous in " + std::to_string(q.zoom_ambiguous.value_or(0)) +
         " of " + std::to_string(q.frames) + " frames (zoom or dolly, zoom or none): confidence lowered";
}

}  // namespace hapcine
