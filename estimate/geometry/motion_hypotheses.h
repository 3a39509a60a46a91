#pragma once
// Which of the motions between two views is the camera's? The two-view
// model selection (model_selection.h) explains the most tracks it can with
// one motion. Where a large subject moves on its own (a face filling half
// the frame, a person walking close by, a crowd), that motion is the
// majority's, and it becomes the camera's: a nodding head turns a still
// camera, a walker makes a pan travel.
//
// The background surrounds the subject: whatever moves in front of it
// covers part of the frame, the background the rest, and in particular the
// frame's border. So a second hypothesis is fitted on the tracks of the
// border band alone (Chebyshev radius >= `border_radius` from the centre,
// the outer ring of the picture), with the same model selection. It
// replaces the majority's when the border holds one dominant motion (its
// fit explains more than half of the border's tracks), the tracks it leaves
// out that the majority explained (the movers) are a group of their own (at
// least `min_correspondences`), and either
//   - the majority's motion does not hold the border (at most half of its
//     tracks): a subject outnumbers the background. A camera that follows a
//     subject keeps its motion: the subject is still in the picture, the
//     border slides, and the border's fit is the camera's; or
//   - the majority's motion nests the border's, the border's is `static`
//     and explains the border better by GRIC (the majority's motion
//     evaluated on the border tracks with the same sigma). *Static* is
//     preferred when the only coherent motion is a region inside the
//     border; a turning or zooming border is not (BorderMotionWins).
//
// The tracks the camera's motion does not explain are outliers of the
// interval (TwoViewResult::inliers); CameraMotion::mover marks those the
// majority explained, which the estimator keeps out of the window's points
// (and so of the in-between frames' solves) when they moved on their own in
// most of the window's intervals.
//
// What it cannot tell: a subject that also holds most of the border; people
// crossing during a pan or a traveling (their motion is consistent with the
// pan plus a small sideways move, or with the traveling: the majority's
// motion nests the border's, which is not still); a traveling whose
// background is at infinity with only a compact near subject showing the
// parallax (it reads as a still camera with a mover).

#include <Eigen/Core>
#include <vector>

#include "estimate/geometry/model_selection.h"

namespace hapcine {

struct MoverOptions {
  bool enabled = true;
  // The border band: tracks whose Chebyshev radius (1 at the frame's edge)
  // is at least this. 0.8 is the outer tenth of the width and height on
  // each side, 36 % of the picture.
  double border_radius = 0.8;
  void Check() const;  // throws UsageError
};

struct CameraMotion {
  TwoViewResult camera;        // the camera's motion; inliers over every match
  bool border_motion = false;  // the border's fit replaced the majority's
  int border_tracks = 0;       // matches in the border band
  int movers = 0;              // matches the majority explained and the camera does not
  std::vector<char> mover;     // per match: one of those (empty unless border_motion)
};

// Chebyshev radius of a normalised point (u = (px - c) / width): 1 on the
// frame's edge. `half_height` = 0.5 * height / width.
double BorderRadius(const Eigen::Vector2d& u, double half_height);

// Squared distance of each match to `r`'s model, in the units of
// TwoViewResult (half the transfer error for homography-type models, the
// Sampson distance for general motion), and the inlier test that goes with
// it at `threshold` (normalised units).
std::vector<double> TwoViewResiduals(const TwoViewResult& r, const std::vector<Eigen::Vector2d>& u1,
                                     const std::vector<Eigen::Vector2d>& u2);
std::vector<char> TwoViewInliers(const TwoViewResult& r, const std::vector<double>& squared_residuals,
                                 double threshold);
// The inlier threshold model_selection.h used for `r`.
double TwoViewThreshold(const TwoViewResult& r, const TwoViewOptions& options);

// SelectTwoViewModel, with the camera's motion told from a subject's (above).
CameraMotion SelectCameraMotion(const std::vector<Eigen::Vector2d>& u1, const std::vector<Eigen::Vector2d>& u2,
                                double f1, double half_height, const TwoViewOptions& options,
                                const MoverOptions& movers);

}  // namespace hapcine
