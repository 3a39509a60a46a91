// TrackCameraEstimator's plane prior for a dolly with a zoom along the
// optical axis (plane_prior.h): the plane is searched among every track of
// the window, not only its points. Kept apart from track_estimator_window.cc:
// one hook in ProcessWindow.

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "estimate/plane_prior.h"
#include "estimate/track_estimator.h"
#include "estimate/window_points.h"

namespace hapcine {
namespace {

// Tracks the plane is searched among.
constexpr int kMaxPlanePoints = 2000;

}  // namespace

PlanePointsFn TrackCameraEstimator::PlanePointsOf(const BaOptions& ba, int held) const {
  const int n = static_cast<int>(keyframes_.size());
  std::vector<const KeyframeTracks*> tracks_at(n);
  for (int i = 0; i < n; ++i) tracks_at[i] = &At(keyframes_[i].pos).u;
  // Every track seen by >= 2 keyframes, triangulated on the solution and
  // kept where it explains them to 1.5 px: the window's points are mostly
  // its longest tracks, and a floor's leave the view soonest.
  const WindowTracks every_track =
      SelectWindowPoints(tracks_at, outlier_tracks_, kMaxPlanePoints, options_.point_grid_cells);
  const double cut = 1.5 * ba.huber_scale;
  return [=](const std::vector<BaCamera>& c) {
    std::vector<BaPoint> p;
    std::vector<BaObservation> o;
    InitWindowPoints(c, every_track, tracks_at, true, 0.0, &p, &o);
    std::vector<char> rigid(p.size(), 1);
    const std::vector<double> e = ObservationErrors(c, p, o, true);
    for (size_t i = 0; i < o.size(); ++i)
      if (!(e[i] <= cut)) rigid[o[i].point] = 0;
    return InverseDepthsIn(c[held], p, rigid);
  };
}

std::vector<int> TrackCameraEstimator::PlaneSupportOf(
    const BaOptions& ba, int held, const std::vector<const std::vector<BaCamera>*>& candidates) const {
  const PlanePointsFn plane_points = PlanePointsOf(ba, held);
  std::vector<int> support;
  for (const auto* c : candidates) {
    const std::optional<PlaneShift> s = ShiftForMotionPlane(*c, held, plane_points(*c));
    support.push_back(s ? s->inliers : 0);
    if (std::getenv("HAPCINE_PLANE_DEBUG")) {
      const BaCamera& a = (*c)[held];
      const BaCamera& b = c->back();
      std::fprintf(stderr, "candidate: forward %.4f zoom %.4f plane %s delta %.4f\n",
                   (a.world_from_cam.conjugate() * (b.center - a.center)).z(), std::exp(b.log_focal - a.log_focal),
                   s ? "yes" : "no", s ? s->delta : 0.0);
    }
  }
  if (std::getenv("HAPCINE_PLANE_DEBUG")) {
    std::fprintf(stderr, "plane_support frame %d:", At(keyframes_.front().pos).tracks.index);
    for (int s : support) std::fprintf(stderr, " %d", s);
    std::fprintf(stderr, "\n");
  }
  return support;
}

void TrackCameraEstimator::ApplyPlanePriorToWindow(const BaOptions& ba, int held, int first_frame,
                                                   std::vector<BaCamera>* cams, std::vector<BaPoint>* pts,
                                                   const std::vector<BaObservation>& obs, BaSummary* summary,
                                                   bool* taken) const {
  const PlanePriorResult r =
      ApplyPlanePrior(ba, held, options_.two_view.noise_floor, PlanePointsOf(ba, held), cams, pts, obs, summary);
  *taken = r.taken;
  if (!std::getenv("HAPCINE_PLANE_DEBUG")) return;
  if (!r.found) {
    std::fprintf(stderr, "plane_prior frame %d: no sloped plane parallel to the move\n", first_frame);
    return;
  }
  std::fprintf(stderr,
               "plane_prior frame %d: w = %.4f x + %.4f y + %.4f (%d of %d points, w %.4f..%.4f), "
               "%d rounds, shift %.4f of the largest w: zoom %.4f -> %.4f, rms %.3f -> %.3f px -> %s\n",
               first_frame, r.shift.plane.x(), r.shift.plane.y(), r.shift.plane.z(), r.shift.inliers, r.shift.points,
               r.shift.min_w, r.shift.max_w, r.rounds, r.total_delta_over_w, std::exp(r.log_zoom_before),
               std::exp(r.log_zoom_after), r.rms_before * width_, r.rms_after * width_, r.taken ? "taken" : "kept");
}

}  // namespace hapcine
