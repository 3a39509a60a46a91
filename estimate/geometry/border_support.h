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

namespace hapcine {

constexpr int kBorderGridCells = 4;

// The share (0-1) of the edge ring's cells holding a point `u[i]` with
// `inlier[i]` set. `u`: normalised coordinates ((px - c) / width, x within
// +-0.5, y within +-half_height); points outside the frame count in the
// nearest cell, points not finite in none. 0 with no inlier (nothing
// supports the motion).
double BorderSupport(const std::vector<Eigen::Vector2d>& u, const std::vector<char>& inlier,
                     double half_height);

}  // namespace hapcine
