#include "estimate/window/plane_prior.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "estimate/bundle/robust_bundle.h"
#include "estimate/window/window_freedoms.h"

namespace hapcine {

PlanePriorResult ApplyPlanePrior(const BaOptions& options, int pivot, double noise_floor,
                                 const PlanePointsFn& plane_points, std::vector<BaCamera>* cameras,
                                 std::vector<BaPoint>* points, const std::vector<BaObservation>& observations,
                                 BaSummary* summary, const PlanePriorOptions& prior) {
  PlanePriorResult r;
  const int n = static_cast<int>(cameras->size());
  if (pivot < 0 || pivot >= n) return r;
  std::vector<BaCamera> cams = *cameras;
  std::vector<BaPoint> pts = *points;
  BaSummary s = *summary;
  BaOptions polish = options;
  for (int round = 0; round < prior.max_rounds; ++round) {
    const std::vector<Eigen::Vector3d> xyw = plane_points(cams);
    const std::optional<PlaneShift> shift = ShiftForMotionPlane(cams, pivot, xyw);
    if (!shift) break;
    if (round == 0) r.shift = *shift;
    r.total_delta_over_w += shift->delta / std::max(shift->max_w, 1e-12);
    std::optional<std::vector<BaCamera>> shifted = ShiftedAxialSolution(cams, pivot, shift->delta);
    if (!shifted) break;
    pts = ShiftedAxialPoints(cams[pivot], shift->delta, pts);
    cams = *std::move(shifted);
    // The soft scale gauge, met where the shift put the cameras: otherwise
    // the polish meets it partly by undoing the shift (both are free).
    if (polish.scale_a >= 0 && polish.scale_b < n)
      polish.scale_distance = (cams[polish.scale_b].center - cams[polish.scale_a].center).norm();
    // The two ends' focals held (see the header).
    cams[pivot].fixed_focal = cams[n - 1].fixed_focal = true;
    PolishBundle(polish, &cams, &pts, observations, &s);
    for (size_t i = 0; i < cams.size(); ++i) cams[i].fixed_focal = (*cameras)[i].fixed_focal;
    r.found = true;
    ++r.rounds;
    // The plane again on the polished solution, until the shift is negligible.
    if (std::abs(shift->delta) <= prior.negligible_share * shift->max_w) break;
  }
  if (!r.found) return r;
  r.log_zoom_before = (*cameras)[n - 1].log_focal - (*cameras)[pivot].log_focal;
  r.log_zoom_after = cams[n - 1].log_focal - cams[pivot].log_focal;
  r.rms_before = summary->rms_after;
  r.rms_after = s.rms_after;
  r.taken = s.success && FitsAsWell(ObservationErrors(*cameras, *points, observations, true),
                                    ObservationErrors(cams, pts, observations, true), noise_floor);
  if (r.taken) {
    *cameras = std::move(cams);
    *points = std::move(pts);
    *summary = s;
  }
  return r;
}

std::vector<char> ContradictedByPlane(const std::vector<int>& support, int min_support) {
  std::vector<char> out(support.size(), 0);
  const int best = support.empty() ? 0 : *std::max_element(support.begin(), support.end());
  if (best < min_support) return out;
  for (size_t c = 0; c < support.size(); ++c) out[c] = 2 * support[c] < best;
  return out;
}

}  // namespace hapcine
