// TrackCameraEstimator, after a window's bundle adjustment (ProcessWindow,
// track_estimator_window.cc; SolveWindow, window_solver.h): the shot's units, the window's frames into the
// raw path, and the start of the next window.

#include <algorithm>
#include <cmath>

#include "core/statistics.h"
#include "estimate/geometry/reference_width.h"
#include "estimate/track_estimator.h"

namespace hapcine {

double PlacedFrameConfidence(double inlier_ratio, double track_quality, double rms_reference_px,
                             const WindowOutcome& w) {
  double c = Clamp01(inlier_ratio) * Clamp01(std::max(track_quality, 0.3)) *
             std::exp(-0.5 * std::pow(rms_reference_px / 2.0, 2)) * (w.focal_observable ? 1.0 : 0.8) *
             ZoomConfidenceFactor(w.report.zoom_decisions);
  if (!w.success) c *= 0.3;
  return c;
}

// Units (camera-path spec): the shot's first translating window scales the
// world about its first keyframe so that the median depth of the points it
// sees is 1; every translating window leaves the median depth seen from its
// last keyframe in scene_depth_ (the next two-view chain's scale).
void TrackCameraEstimator::SetUnits(std::vector<BaPoint>* points) {
  auto depths_from = [&](const BaCamera& cam) {
    std::vector<double> depths;
    for (const auto& p : *points) {
      if (!(p.homogeneous(3) > 1e-12)) continue;
      const Eigen::Vector3d X = p.anchor + p.homogeneous.head<3>() / p.homogeneous(3);
      const double z = (cam.world_from_cam.conjugate() * (X - cam.center)).z();
      if (z > 0 && std::isfinite(z)) depths.push_back(z);
    }
    return depths;
  };
  const BaCamera origin = keyframes_[0].cam;
  const double m = Median(depths_from(origin));
  if (!scale_set_ && m > 0) {
    const double k = 1 / m;  // scale about the first keyframe's centre
    for (auto& kf : keyframes_) kf.cam.center = origin.center + (kf.cam.center - origin.center) * k;
    for (auto& p : *points) {
      p.anchor = origin.center + (p.anchor - origin.center) * k;
      p.homogeneous(3) /= k;
      p.homogeneous.normalize();
    }
    scale_set_ = true;
  }
  const double last = Median(depths_from(keyframes_.back().cam));
  if (last > 0) scene_depth_ = last;
}

// The window's frames into raw_: keyframes as solved, the others by a
// pose-only solve against the window's points with only their segment
// model's freedoms, started from the slerp/lerp of the neighbouring keyframes.
void TrackCameraEstimator::EmitWindowFrames(const WindowOutcome& w, bool final) {
  const int n = static_cast<int>(keyframes_.size());
  const int emit_end = final ? buffer_start_ + static_cast<int>(frames_.size())
                             : keyframes_[n - 2].pos;  // exclusive
  const int emit_begin =
      raw_.empty() ? 0 : raw_.back().meta.index - frames_.front().tracks.index + buffer_start_ + 1;
  int ki = 0;
  for (int pos = emit_begin; pos < emit_end; ++pos) {
    const BufferedFrame& f = At(pos);
    RawPose out;
    out.meta = f.tracks;
    while (ki + 1 < n && keyframes_[ki + 1].pos <= pos) ++ki;
    if (pos < keyframes_[0].pos) {
      // Before the shot's first usable frame (a blank lead-in, a fade in):
      // nothing places these frames; the placeholder is the origin.
      raw_.push_back(LostPose(f.tracks, keyframes_[0].cam));
      continue;
    }
    const Keyframe& a = keyframes_[ki];
    if (pos == a.pos) {
      out.cam = a.cam;
      out.model = ki == 0 && n > 1 ? keyframes_[1].model : a.model;
      if (a.fixed && ki == 0 && n > 1) out.model = keyframes_[1].model;
      out.confidence =
          PlacedFrameConfidence(a.inlier_ratio, f.tracks.quality, w.rms_px * kReferenceWidthPx / width_, w);
      raw_.push_back(out);
      continue;
    }
    if (!f.usable) {
      // A blank frame, or one with too few tracks: its own image gives no
      // evidence of the pose. Even between two placed keyframes it stays
      // lost rather than interpolated: a blank frame is a flash, a fade or a
      // whip, where the motion in between is not smooth enough to guess.
      raw_.push_back(LostPose(f.tracks, raw_.empty() ? a.cam : raw_.back().cam));
      continue;
    }
    if (ki + 1 >= n) {
      // Trailing frames with tracks (end of shot): pose-only solve with the last model's freedoms.
      out.cam = raw_.empty() ? a.cam : raw_.back().cam;
      out.model = a.model;
    }
    const Keyframe& b = ki + 1 < n ? keyframes_[ki + 1] : keyframes_[ki];
    const double t = b.pos > a.pos ? static_cast<double>(pos - a.pos) / (b.pos - a.pos) : 0;
    out.cam.world_from_cam = a.cam.world_from_cam.slerp(t, b.cam.world_from_cam);
    out.cam.center = (1 - t) * a.cam.center + t * b.cam.center;
    out.cam.log_focal = (1 - t) * a.cam.log_focal + t * b.cam.log_focal;
    out.cam.rotation_source = out.cam.center_source = out.cam.focal_source = -1;
    out.model = ki + 1 < n ? b.model : a.model;
    std::vector<BaObservation> fobs;
    for (const auto& [id, u] : f.u) {
      auto it = w.point_of_track.find(id);
      if (it != w.point_of_track.end() && w.point_kept[it->second])
        fobs.push_back({0, it->second, u});
    }
    PoseFreedoms fr;
    fr.rotation = HasRotation(out.model);
    fr.center = HasTranslation(out.model);
    fr.focal = HasZoom(out.model);
    double rms_px = w.rms_px;
    if (static_cast<int>(fobs.size()) >= options_.min_tracks && w.success &&
        (fr.rotation || fr.center || fr.focal)) {
      BaOptions po = w.pose_options;
      po.max_iterations = 10;
      BaCamera cam = out.cam;
      const BaSummary ps = SolvePose(&cam, fr, w.points, fobs, po);
      if (ps.success && cam.world_from_cam.coeffs().allFinite() && cam.center.allFinite() &&
          std::isfinite(cam.log_focal)) {
        out.cam = cam;
        rms_px = ps.rms_after * width_;
      }
    }
    out.confidence =
        PlacedFrameConfidence(b.inlier_ratio, f.tracks.quality, rms_px * kReferenceWidthPx / width_, w);
    raw_.push_back(out);
  }
}

// The next window starts with the last two keyframes, held constant; the
// frames before them are done.
void TrackCameraEstimator::StartNextWindow() {
  std::vector<Keyframe> lead_in(keyframes_.end() - 2, keyframes_.end());
  for (Keyframe& k : lead_in) {
    k.fixed = k.fixed_focal = true;
    k.chain_start = false;
  }
  keyframes_ = std::move(lead_in);
  const int drop = keyframes_.front().pos - buffer_start_;
  frames_.erase(frames_.begin(), frames_.begin() + drop);
  buffer_start_ = keyframes_.front().pos;
  outlier_tracks_.clear();
  mover_intervals_.clear();
}

}  // namespace hapcine
