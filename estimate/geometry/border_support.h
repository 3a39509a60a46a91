#pragma once
// How much of the frame's edge confirms a camera motion. The background
// surrounds whatever moves in front of it (motion_hypotheses.h): a camera
// that moves shifts the whole picture, so the tracks its motion explains
// reach around the frame's edge wherever there is texture. A motion whose
// inliers hold only a region inside the picture (a face filling the frame
// over a dark, defocused background that gives no tracks) has no
// independent evidence: the region may be moving on its own, and the border
// rule (SelectCameraMotion) cannot tell, having no background tracks to fit.
//
// The measure: the frame cut into kBorderGridCells x kBorderGridCells
// cells, the share of the ring of cells touching the frame's edge (12 of
// 16) that hold at least one inlier. A 4 x 4 grid: each edge cell is a
// quarter of the width or height, large enough that a textured scene fills
// each with some of the ~100-300 tracks of an interval, fine enough that a
// compact region leaves most of the ring empty.

#include <Eigen/Core>
#include <vector>

#include "estimate/geometry/model_selection.h"

namespace hapcine {

constexpr int kBorderGridCells = 4;
// Below this border support the motion rests on a region inside the picture
// (most of the edge cells hold none of its inliers).
constexpr double kUnconfirmedBorderSupport = 0.5;

// The share (0-1) of the edge ring's cells holding a point `u[i]` with
// `inlier[i]` set. `u`: normalised coordinates ((px - c) / width, x within
// +-0.5, y within +-half_height); points outside the frame count in the
// nearest cell, points not finite in none. 0 with no inlier (nothing
// supports the motion).
double BorderSupport(const std::vector<Eigen::Vector2d>& u, const std::vector<char>& inlier,
                     double half_height);

// A still border around a subject's motion. Where a camera turns or
// zooms, every part of the picture moves with it but an overlay and what
// lies exactly at the depth where its translation cancels its turn; tracks
// at the frame's border that stay where they were while the interval's
// turn and zoom would move them are the background of a still camera, and
// the motion is a subject's. Counted over the matches in the border band
// (Chebyshev radius >= `border_radius`, motion_hypotheses.h) that
// `motion`'s rotation and zoom (its homography at infinity) move by at
// least twice `threshold` (normalised units): `moved_by_turn` of them, and
// `still` of those that moved at most `threshold` (the still reading a
// threshold clear of the moving one). A translation alone leaves far
// points still and tests none.
struct StillBorder {
  int moved_by_turn = 0;
  int still = 0;
};
StillBorder StillBorderTracks(const TwoViewResult& motion, const std::vector<Eigen::Vector2d>& u1,
                              const std::vector<Eigen::Vector2d>& u2, double threshold,
                              double half_height, double border_radius);

// The shot rule, over its keyframe intervals (two parallel lists, in any
// order): `support` each interval's border support (1 for a still one), `border` its still border
// (StillBorderTracks; an interval whose turn and zoom move fewer than
// kMinStillBorderTracks of the border's tracks tests nothing: a still
// camera, a translation, a turn under the noise). The shot is a still
// camera before a moving subject when the border stays still in most of the
// intervals that test it (at least kMinStillBorderTracks still tracks in
// more than half of them: persistent, so a stray stuck track or a moment of
// overlay does not make a shot still) and either
//   - its motion is unconfirmed (median support below
//     kUnconfirmedBorderSupport, the doubtful rule of shot_quality.h): no
//     background follows the motion, and the background there is still; or
//   - most of the border tracks its turn and zoom would move stayed still
//     (summed over the tested intervals): a subject that reaches the edge
//     holds the rest.
// An overlay on a real camera motion (a logo) is a small share of a border
// that moves; with no tracks at the border at all (an object turned before
// an empty background) nothing contradicts the motion, and it stays.
constexpr int kMinStillBorderTracks = 3;
bool StillBorderAroundMotion(const std::vector<double>& support,
                             const std::vector<StillBorder>& border);

}  // namespace hapcine
