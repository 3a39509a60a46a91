#pragma once
// The prior that picks a depth for a dolly with a zoom along the optical
// axis, where the images leave every inverse depth open by one shift
// (axial_ambiguity.h): the shift that makes a sloped plane among the points,
// the floor under the dolly or a wall beside it (motion_plane.h), parallel to
// the move. docs/estimate.md, "Algorithm", step 4.

#include <functional>
#include <vector>

#include "estimate/window/axial_ambiguity.h"
#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

struct PlanePriorOptions {
  int max_rounds = 4;             // shift and polish, until the shift is negligible
  double negligible_share = 0.01; // of the points' largest inverse depth
};

struct PlanePriorResult {
  bool found = false;  // a sloped plane, and a shift that keeps every point in front
  bool taken = false;  // the shifted solution fits as well (FitsAsWell) and replaced the input
  int rounds = 0;
  PlaneShift shift;                // the first round's
  double total_delta_over_w = 0;   // the rounds' shifts, each over its points' largest w
  double log_zoom_before = 0, log_zoom_after = 0;  // log f of the last camera over the pivot's
  double rms_before = 0, rms_after = 0;            // normalised units, the solve's own observations
};

// Points (x, y, w) in the pivot camera (InverseDepthsIn) of the solution
// `cams`, the plane is searched among.
using PlanePointsFn = std::function<std::vector<Eigen::Vector3d>(const std::vector<BaCamera>& cams)>;

// Moves a solved window whose cameras after `pivot` translate along its
// optical axis along the ambiguity (cameras and points, ShiftedAxialSolution
// and ShiftedAxialPoints), then polishes it with the focals of the pivot and
// of the last camera held. Why held: every term of the fit is flat along the
// shift but the focal smoothness prior, so a polish free to move every focal
// wanders along it while it takes up the map's inexactness off the axis (a
// lateral drift of the centres by 1/2000 of the move costs ~0.1 px): 9 % of
// zoom in a unit test, and that prior pulls back to where the fit started.
// The two ends' focals block the shift (it changes the last one most); the
// focals between them are free to follow the tracks, which also undoes the
// bend that prior left in the first solve of a strong zoom (on a dolly zoom
// over a floor, holding them all: 0.95 % of zoom error; the ends only:
// 0.21 %). Repeated on
// the polished solution until the shift is negligible. The result replaces
// the input only when it fits as well (FitsAsWell).
PlanePriorResult ApplyPlanePrior(const BaOptions& options, int pivot, double noise_floor,
                                 const PlanePointsFn& plane_points, std::vector<BaCamera>* cameras,
                                 std::vector<BaPoint>* points, const std::vector<BaObservation>& observations,
                                 BaSummary* summary, const PlanePriorOptions& prior = {});

// The branch of the axial ambiguity a floor decides. `support[c]`: the
// points of the plane the prior would use under candidate c (0: none). On
// the wrong branch the depth order is flipped: a floor's inverse depth falls
// towards the bottom of the image, and no shift makes it parallel to the
// move without putting its own points beyond infinity, so that candidate
// has no such plane. Ruled out: the candidates with under half of the best
// support (a slab through a cluster can give the wrong branch a few points),
// when the best has at least `min_support` points; otherwise none (no
// evidence).
std::vector<char> ContradictedByPlane(const std::vector<int>& support, int min_support = 24);

}  // namespace hapcine
