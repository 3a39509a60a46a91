#pragma once
// The axial dolly/zoom ambiguity.
//
// A camera that translates along its optical axis while its focal length
// changes moves every image point radially about the principal point. Point
// i scales by 1/s_i(t) = a(t) + b(t) w_i (w_i its inverse depth, a the zoom,
// b the forward motion), and any affine change of the inverse depths
// w' = alpha + beta w explains the same tracks with another zoom a' and
// motion b'. With beta < 0 the depth order flips: a forward dolly zooming
// out (a dolly zoom) fits exactly as a backward move at constant focal with the
// subject at infinity and the background near. Only cheirality (no point
// beyond infinity, enforced in the bundle adjustment) separates the two
// branches, so both must be optimised and compared; a solve started on one
// branch stays on it. Inside the right branch the zoom is pinned by the
// points that can be pushed no further: the initialisation puts the most
// distant points at infinity, the smallest zoom the tracks allow.

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// True when the centres after `pivot` moved mostly along the pivot camera's
// optical axis (|forward component| >= `min_axial_share` of the distance).
bool IsAxialMotion(const std::vector<BaCamera>& cams, int pivot, double min_axial_share = 0.8);

// Which way the centre farthest from `pivot`'s moved along the pivot
// camera's optical axis: +1 forward, -1 backward, 0 no move.
int AxialDirection(const std::vector<BaCamera>& cams, int pivot);

// A branch cue (occlusion order, a floor parallel to the move) tells the two
// branches of the ambiguity apart: they move opposite ways along the axis
// with the depth order flipped. Two solutions that move the same way share
// the depth order and differ by a shift of the inverse depths (how much of
// the scaling is zoom), which such a cue does not see. So of the candidates
// the cue rules out (`ruled_out`), only those that move against the
// best-scored candidate it keeps (`score`: its evidence, e.g. the votes' z or
// the plane's support) stay out; `direction[c]` is AxialDirection of c.
// Unchanged when the cue rules out none or all, or the best does not move.
std::vector<char> RuledOutOtherBranch(const std::vector<char>& ruled_out, const std::vector<int>& direction,
                                      const std::vector<double>& score);

// Radial scale of matches (u1 -> u2, normalised coordinates about the
// principal point) at `percentile` in [0, 1]; points closer than `min_radius`
// to the centre are skipped (their scale is noise). 1 if none is usable.
double RadialScalePercentile(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& matches,
                             double percentile, double min_radius = 0.1);

// The other branch of the ambiguity as an initialisation: the centres after
// `pivot` mirrored through the pivot's centre, and the focal of each
// keyframe k > pivot chained from the radial scale of its matches with
// keyframe k - 1 (matches[k]): a forward move takes a low percentile (the
// far points, which shrink or grow least, are put at infinity), a backward
// move a high one. Rotations and sharing are kept.
std::vector<BaCamera> MirroredAxialBranch(
    const std::vector<BaCamera>& cams, int pivot,
    const std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>>& matches);

// Points (x, y, w) in `cam`: normalised image coordinates and inverse depth
// (0 at infinity) of the points with `used[i]`, those in front of it only.
std::vector<Eigen::Vector3d> InverseDepthsIn(const BaCamera& cam, const std::vector<BaPoint>& points,
                                             const std::vector<char>& used);

// The solution moved along the ambiguity by `delta`: every inverse depth in
// the pivot camera becomes w + delta, i.e. the projective map X' = X / (1 +
// delta Z) of the pivot's frame. A camera at Z = c along the pivot's axis
// goes to c / (1 + delta c), its focal to f / (1 + delta c): the tracks are
// the same for a move exactly along the axis (otherwise to first order; a
// solve polishes). Nothing when a camera would pass to or behind the plane
// Z = -1/delta, or a fixed camera is not at the pivot's centre (the move
// before the pivot already pins the depths).
std::optional<std::vector<BaCamera>> ShiftedAxialSolution(const std::vector<BaCamera>& cams, int pivot,
                                                          double delta);

// The points under the same map (pivot: the camera of `cams` before the
// shift); each anchor moves with the map, so it stays its camera's centre.
std::vector<BaPoint> ShiftedAxialPoints(const BaCamera& pivot, double delta, const std::vector<BaPoint>& points);

// Where the window moves along the pivot's optical axis and the points
// `xyw` (InverseDepthsIn the pivot camera) show a sloped plane
// (motion_plane.h): the shift that makes that plane contain the direction of
// motion, as a floor under a dolly does. Nothing without such a plane, or
// when the shift would put points beyond infinity (the plane is not parallel
// to the move).
struct PlaneShift {
  double delta = 0;                                 // inverse depth shift in the pivot camera
  Eigen::Vector3d plane = Eigen::Vector3d::Zero();  // w = plane . (x, y, 1) before the shift
  int inliers = 0, points = 0;
  double min_w = 0, max_w = 0;                      // smallest and largest inverse depth before the shift
};
std::optional<PlaneShift> ShiftForMotionPlane(const std::vector<BaCamera>& cams, int pivot,
                                              const std::vector<Eigen::Vector3d>& xyw);

}  // namespace hapcine
