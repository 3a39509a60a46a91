#include "estimate/shot_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "core/csv.h"
#include "core/statistics.h"
#include "estimate/geometry/reference_width.h"
#include "estimate/window/zoom_evidence.h"

namespace hapcine {
namespace {

// The windows' figures per shot: inliers and correspondences summed, the
// RMS pooled over observations.
struct WindowTally {
  long inliers = 0, correspondences = 0;
  double sum_sq_px = 0;
  long observations = 0;
  bool focal_observable = false;
  bool held_still = false;
  std::vector<double> border_support;  // per keyframe interval
};

// The frame's confidence as its file states it (a float held value, read as
// the double of its shortest text: 0.3, not 0.30000001192092896).
double ConfidenceAsWritten(const CameraFrame& f) {
  if (!f.confidence) return 1.0;
  return std::strtod(FormatFloat((*f.confidence).raw()).c_str(), nullptr);
}

// Whether the decision that left the window ambiguous, its least decisive,
// kept the zoom (after PreferNoZoom / PreferOtherBranch: what was written).
bool AmbiguityKeptZoom(const std::vector<ZoomDecision>& decisions) {
  const auto least = std::min_element(decisions.begin(), decisions.end(), [](const auto& a, const auto& b) {
    return Decisiveness(a) < Decisiveness(b);
  });
  return least != decisions.end() && least->zoom_taken;
}

// Frames of shot `q` written by windows with an ambiguous zoom decision
// (q->zoom_ambiguous), and of them those whose window kept the zoom: each
// window writes the frames after the previous window's last, up to its own.
void CountZoomAmbiguousFrames(const std::vector<WindowReport>& windows, ShotQuality* q) {
  int frames = 0, kept_zoom = 0, written_up_to = q->first_frame - 1;
  for (const WindowReport& w : windows) {
    if (w.shot != q->shot) continue;
    const int first = std::max(written_up_to + 1, q->first_frame), last = std::min(w.last_frame, q->last_frame);
    if (WindowZoomAmbiguous(w.zoom_decisions) && last >= first) {
      frames += last - first + 1;
      kept_zoom += AmbiguityKeptZoom(w.zoom_decisions) ? last - first + 1 : 0;
    }
    written_up_to = std::max(written_up_to, w.last_frame);
  }
  q->zoom_ambiguous = frames;
  if (frames > 0) q->ambiguous_zoom_kept = kept_zoom;
}

}  // namespace

bool UnconfirmedMotion(const ShotQuality& q) {
  return !q.still_border && q.border_support && *q.border_support < kDoubtfulBorderSupport;
}

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
    t.held_still |= w.shot_held_still;
    t.border_support.insert(t.border_support.end(), w.border_support.begin(),
                            w.border_support.end());
  }
  std::vector<ShotQuality> out;
  // A shot's frames need not be contiguous (stills shots linked across a
  // split, stills_groups.h): each shot collects its frames wherever they are.
  std::map<int, size_t> index_of_shot;
  std::vector<std::vector<double>> confidence;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    const CameraFrame& f = path.frames[i];
    const int shot = f.shot.value_or(0);
    if (index_of_shot.emplace(shot, out.size()).second) {
      out.push_back({});
      out.back().shot = shot;
      out.back().first_frame = f.frame;
      confidence.emplace_back();
    }
    ShotQuality& q = out[index_of_shot[shot]];
    q.last_frame = f.frame;
    ++q.frames;
    q.lost += IsLost(f);
    confidence[index_of_shot[shot]].push_back(IsLost(f) ? 0.0 : ConfidenceAsWritten(f));
  }
  for (size_t k = 0; k < out.size(); ++k) out[k].median_confidence = Median(confidence[k]);
  for (ShotQuality& q : out) {
    if (auto it = tally.find(q.shot); it != tally.end()) {
      const WindowTally& t = it->second;
      if (t.correspondences > 0) q.inlier_ratio = static_cast<double>(t.inliers) / t.correspondences;
      if (t.observations > 0 && width > 0)
        q.rms_px = std::sqrt(t.sum_sq_px / t.observations) * kReferenceWidthPx / width;
      q.focal_observable = t.focal_observable;
      if (!t.border_support.empty()) q.border_support = Median(t.border_support);
      q.still_border = t.held_still;
      // A shot held still writes no zoom: no zoom decision of its windows stands.
      if (q.still_border) {
        q.zoom_ambiguous = 0;
      } else {
        CountZoomAmbiguousFrames(windows, &q);
      }
    }
    q.doubtful = q.lost > kDoubtfulLostShare * q.frames ||
                 q.median_confidence < kDoubtfulMedianConfidence || UnconfirmedMotion(q);
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
          {"ambiguous_zoom_kept", opt(q.ambiguous_zoom_kept)},
          {"border_support", opt(q.border_support)},
          {"still_border", q.still_border},
          {"doubtful", q.doubtful}};
}

std::string DoubtfulShotLine(const ShotQuality& q) {
  std::string s = "shot " + std::to_string(q.shot) + " (frames " + std::to_string(q.first_frame) + "-" +
                  std::to_string(q.last_frame) + "): doubtful: ";
  if (q.lost > 0) s += std::to_string(q.lost) + " of " + std::to_string(q.frames) + " frames lost, ";
  s += "median confidence " + FormatFixed(q.median_confidence, 2);
  if (UnconfirmedMotion(q))
    s += ", border support " + FormatFixed(*q.border_support, 2) +
         " (the motion rests on a region inside the picture)";
  return s;
}

std::string StillBorderLine(const ShotQuality& q) {
  std::string s =
      "shot " + std::to_string(q.shot) + " (frames " + std::to_string(q.first_frame) + "-" +
      std::to_string(q.last_frame) +
      "): read as a still camera: the frame's border stays where its motion would move it";
  if (q.border_support) s += " (border support " + FormatFixed(*q.border_support, 2) + ")";
  return s + ": a subject's motion, not the camera's";
}

std::string AmbiguousZoomLine(const ShotQuality& q) {
  const int frames = q.zoom_ambiguous.value_or(0);
  std::string s = "shot " + std::to_string(q.shot) + " (frames " + std::to_string(q.first_frame) + "-" +
                  std::to_string(q.last_frame) + "): zoom ambiguous in " + std::to_string(frames) + " of " +
                  std::to_string(q.frames) + " frames (zoom or dolly, zoom or none): ";
  if (q.ambiguous_zoom_kept) {
    const int zoom = std::clamp(*q.ambiguous_zoom_kept, 0, frames);
    if (zoom == frames) s += "the zoom kept, ";
    else if (zoom == 0) s += "the reading without zoom kept, ";
    else s += "the zoom kept in " + std::to_string(zoom) + ", the reading without zoom in " +
              std::to_string(frames - zoom) + ", ";
  }
  return s + "confidence lowered";
}

}  // namespace hapcine
