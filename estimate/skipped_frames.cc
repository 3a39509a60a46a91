#include "estimate/skipped_frames.h"

#include <algorithm>
#include <cmath>

#include "core/rotation.h"

namespace hapcine {
namespace {

CameraFrame Between(const CameraFrame& a, const CameraFrame& b, const SkippedFrame& s, int width) {
  const double span = b.time_s - a.time_s;
  const double u = span > 0 ? std::clamp((s.time_s - a.time_s) / span, 0.0, 1.0) : 0.5;
  CameraFrame f = b;
  f.frame = s.index;
  f.time_s = s.time_s;
  f.world_from_cam = a.world_from_cam.slerp(u, b.world_from_cam).normalized();
  f.center = (1 - u) * a.center + u * b.center;
  // Focal: geometric, through the field of view when no focal column.
  const double fa = a.focal_px ? *a.focal_px : FocalPxFromFovDeg(a.fov_deg, width);
  const double fb = b.focal_px ? *b.focal_px : FocalPxFromFovDeg(b.fov_deg, width);
  const double focal = std::exp((1 - u) * std::log(fa) + u * std::log(fb));
  if (a.focal_px && b.focal_px) f.focal_px = focal;
  f.fov_deg = FovDegFromFocalPx(focal, width);
  if (a.confidence && b.confidence) f.confidence = kSkippedFrameConfidence * std::min(*a.confidence, *b.confidence);
  return f;
}

// Lost (docs/formats.md): the pose of `from`, the nearest placed frame, is
// only a placeholder.
CameraFrame Lost(const CameraFrame& from, const SkippedFrame& s) {
  CameraFrame f = from;
  f.frame = s.index;
  f.time_s = s.time_s;
  f.model = kLostModel;
  f.confidence = 0;
  return f;
}

}  // namespace

void InsertSkippedFrames(const std::vector<SkippedFrame>& skipped, int width_px, CameraPath* path) {
  if (skipped.empty() || path->frames.empty()) return;
  const int width = width_px > 0 ? width_px : 1000;  // fov alone does not depend on it
  const std::vector<CameraFrame>& est = path->frames;
  std::vector<CameraFrame> out;
  out.reserve(est.size() + skipped.size());
  size_t next = 0;  // first estimated frame not yet copied
  for (const SkippedFrame& s : skipped) {
    while (next < est.size() && est[next].frame < s.index) out.push_back(est[next++]);
    if (next < est.size() && est[next].frame == s.index) continue;  // not skipped after all
    const bool has_before = next > 0, has_after = next < est.size();
    // Placed only between two placed frames of one shot: the motion is then
    // bounded on both sides and smooth at the scale of a frame. Next to a
    // lost frame, at either end or across a shot boundary one side is
    // unknown, and holding or extrapolating would invent the motion.
    if (has_before && has_after && est[next - 1].shot == est[next].shot && !IsLost(est[next - 1]) &&
        !IsLost(est[next]))
      out.push_back(Between(est[next - 1], est[next], s, width));
    else
      out.push_back(Lost(has_before ? est[next - 1] : est[next], s));
  }
  while (next < est.size()) out.push_back(est[next++]);
  path->frames = std::move(out);
}

}  // namespace hapcine
