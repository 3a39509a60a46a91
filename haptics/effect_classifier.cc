#include "haptics/effect_classifier.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/rotation.h"
#include "haptics/camera_signals.h"

namespace hapcine {
namespace {

double Correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = a.size();
  if (n < 3) return 0;
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0;
}

double Sign(double v) { return v < 0 ? -1.0 : 1.0; }

// The segment's motion: translation in depth units of the start camera's
// frame, accumulated angles, zoom change and the z/zoom correlation.
ClassifiedSegment MeasureSegment(const CameraPath& path, const ShotRange& shot,
                                 const CameraSignals& s, size_t i0, size_t i1, double depth) {
  ClassifiedSegment c;
  c.segment.start_s = s.time_s[i0];
  c.segment.end_s = s.time_s[i1];
  const auto& f0 = path.frames[shot.first + i0];
  const auto& f1 = path.frames[shot.first + i1];
  const Eigen::Matrix3d world_from_start = f0.world_from_cam.toRotationMatrix();
  c.translation = world_from_start.transpose() * (f1.center - f0.center) / depth;
  // Accumulate frame-to-frame angle changes so turns beyond 180 deg count.
  for (size_t i = i0 + 1; i <= i1; ++i) {
    c.tilt_rad += s.tilt_rad[i] - s.tilt_rad[i - 1];
    c.pan_rad += s.pan_rad[i] - s.pan_rad[i - 1];
    c.roll_rad += s.roll_rad[i] - s.roll_rad[i - 1];
  }
  c.log_zoom = s.log_zoom[i1] - s.log_zoom[i0];
  std::vector<double> z, lz;
  for (size_t i = i0; i <= i1; ++i) {
    z.push_back(s.position_u[i].z());
    lz.push_back(s.log_zoom[i]);
  }
  c.z_zoom_correlation = Correlation(z, lz);
  return c;
}

// A segment dominated by rotation: tilt, roll, or a pan (labelled as the
// traveling it follows).
void LabelRotation(const ClassifiedSegment& c, EffectSegment* e) {
  const double rt = std::abs(c.tilt_rad), rp = std::abs(c.pan_rad), rr = std::abs(c.roll_rad);
  if (rt >= rp && rt >= rr) {
    e->effect = CameraEffect::kTilting;
    e->intensity = Sign(c.tilt_rad);
  } else if (rr >= rp) {
    e->effect = CameraEffect::kDutchAngle;
    e->intensity = Sign(c.roll_rad);
  } else {
    e->effect = CameraEffect::kTraveling;
    e->intensity = -Sign(c.pan_rad);  // pan left (+) follows something moving left
  }
}

// A segment dominated by translation: crane (vertical), traveling (sideways)
// or a dolly along the view (labelled as a zoom).
void LabelTranslation(const Eigen::Vector3d& t, EffectSegment* e) {
  const double tx = std::abs(t.x()), ty = std::abs(t.y()), tz = std::abs(t.z());
  if (ty >= tx && ty >= tz) {
    e->effect = CameraEffect::kCraneShot;
    e->intensity = Sign(t.y());
  } else if (tx >= tz) {
    e->effect = CameraEffect::kTraveling;
    e->intensity = Sign(t.x());
  } else {
    e->effect = CameraEffect::kZoomIn;  // dolly in/out
    e->intensity = -Sign(t.z());
  }
}

ClassifiedSegment Label(const CameraPath& path, const ShotRange& shot, const CameraSignals& s,
                        size_t i0, size_t i1, double depth, const ClassifierOptions& o) {
  ClassifiedSegment c = MeasureSegment(path, shot, s, i0, i1, depth);
  const double sig = o.significant_change;
  const double tx = std::abs(c.translation.x()), ty = std::abs(c.translation.y()),
               tz = std::abs(c.translation.z());
  const double rp = std::abs(c.pan_rad);
  const double zm = std::abs(c.log_zoom);
  const double t_max = std::max({tx, ty, tz});
  const double r_max = std::max({std::abs(c.tilt_rad), rp, std::abs(c.roll_rad)});
  EffectSegment& e = c.segment;
  e.intensity = 1;
  auto comparable = [](double a, double b) { return a > 0.25 * b && b > 0.25 * a; };
  // The ratio of forward travel to zoom depends on the unknown subject
  // distance (and on the path's units), so vertigo only asks for both
  // movements together, in the dolly-zoom directions, within a factor 20.
  if (zm > sig && tz > sig && c.translation.z() * c.log_zoom > 0 && tz < 20 * zm && zm < 20 * tz &&
      c.z_zoom_correlation > 0.8) {
    // Forward (z decreasing) with a zoom-out (log_zoom decreasing): dolly zoom.
    e.effect = CameraEffect::kVertigo;
    e.intensity = c.translation.z() < 0 ? 1 : -1;
  } else if (zm > sig && zm >= 0.5 * std::max(t_max, r_max)) {
    e.effect = CameraEffect::kZoomIn;
    e.intensity = Sign(c.log_zoom);
  } else if (rp > sig && tx > sig && c.translation.x() * c.pan_rad > 0 && comparable(tx, rp) &&
             tx >= ty) {
    e.effect = CameraEffect::kArcing;
  } else if (t_max > sig && t_max >= 0.5 * r_max) {
    LabelTranslation(c.translation, &e);
  } else if (r_max > sig) {
    LabelRotation(c, &e);
  } else {
    e.effect = CameraEffect::kNone;
  }
  return c;
}

}  // namespace

void ClassifierOptions::Check() const {
  if (!(reference_depth_u >= 0)) throw UsageError("classifier reference depth must be >= 0");
  if (!(energy_threshold > 0)) throw UsageError("classifier energy threshold must be > 0");
  if (!(smoothing_s >= 0 && merge_gap_s >= 0 && min_segment_s >= 0)) {
    throw UsageError("classifier durations must be >= 0");
  }
  if (!(significant_change > 0)) throw UsageError("classifier significant_change must be > 0");
}

std::vector<ClassifiedSegment> ClassifyCameraPath(const CameraPath& read_path,
                                                  const ClassifierOptions& o) {
  o.Check();
  // Lost frames hold their placeholder and the gap after them is closed:
  // no motion, no spike (JoinAcrossLostFrames).
  const std::optional<CameraPath> joined = JoinAcrossLostFrames(read_path);
  const CameraPath& path = joined ? *joined : read_path;
  const double depth = o.reference_depth_u > 0 ? o.reference_depth_u : ReferenceDepthFor(path, 1.0);
  std::vector<ClassifiedSegment> out;
  for (const ShotRange& shot : SplitShots(path)) {
    const CameraSignals s = ExtractShotSignals(path, shot, depth);
    const size_t n = s.size();
    if (n < 2) continue;
    // Energy: net change over a window of +-smoothing_s / 2 divided by its
    // duration (a net displacement, so zero-mean jitter mostly cancels,
    // unlike an average of absolute frame-to-frame speeds).
    std::vector<bool> active(n);
    size_t lo = 0, hi = 0;
    for (size_t i = 0; i < n; ++i) {
      while (s.time_s[lo] < s.time_s[i] - o.smoothing_s / 2) ++lo;
      while (hi + 1 < n && s.time_s[hi + 1] <= s.time_s[i] + o.smoothing_s / 2) ++hi;
      size_t a = lo, b = std::max(hi, i);
      if (b == a) b = std::min(a + 1, n - 1);
      if (b == a && a > 0) a = b - 1;
      const double dt = s.time_s[b] - s.time_s[a];
      const auto& fa = path.frames[shot.first + a];
      const auto& fb = path.frames[shot.first + b];
      const double v_t = (fb.center - fa.center).norm() / depth;
      const double v_r = DegToRad(AngleBetweenDeg(fa.world_from_cam, fb.world_from_cam));
      const double v_z = std::abs(s.log_zoom[b] - s.log_zoom[a]);
      active[i] = dt > 0 && std::max({v_t, v_r, v_z}) / dt > o.energy_threshold;
    }
    // Runs, merged across short gaps, short ones dropped.
    std::vector<std::pair<size_t, size_t>> runs;
    for (size_t i = 0; i < n; ++i) {
      if (!active[i]) continue;
      size_t j = i;
      while (j + 1 < n && active[j + 1]) ++j;
      if (!runs.empty() && s.time_s[i] - s.time_s[runs.back().second] < o.merge_gap_s) {
        runs.back().second = j;
      } else {
        runs.push_back({i, j});
      }
      i = j;
    }
    for (const auto& r : runs) {
      if (s.time_s[r.second] - s.time_s[r.first] < o.min_segment_s) continue;
      ClassifiedSegment c = Label(path, shot, s, r.first, r.second, depth, o);
      if (c.segment.effect != CameraEffect::kNone) out.push_back(c);
    }
  }
  return out;
}

std::vector<EffectSegment> ClassifyEffects(const CameraPath& path, const ClassifierOptions& o) {
  std::vector<EffectSegment> segs;
  for (const auto& c : ClassifyCameraPath(path, o)) segs.push_back(c.segment);
  return segs;
}

}  // namespace hapcine
