#pragma once
// A plane the camera moves parallel to: the floor under a dolly, the walls or
// ceiling of a corridor. Along the optical axis the images cannot tell a
// dolly with a zoom from one through a scene whose inverse depths are all
// shifted by a constant (axial_ambiguity.h); a dolly rides on the floor, so
// the shift that puts the floor's horizon through the direction of motion is
// the one a real set has. docs/estimate.md, "Algorithm", step 4.
//
// In a camera's frame a plane n . X = 1 has inverse depth w = n . (x, y, 1)
// over normalised image coordinates (x, y): a plane in (x, y, w). A plane
// facing the camera (a back wall, a subject) has w nearly constant; the
// search keeps only planes whose inverse depth changes across their points.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

namespace hapcine {

struct InverseDepthPlane {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // w = n . (x, y, 1)
  int inliers = 0;
};

struct PlaneSearchOptions {
  // Inlier tolerance on w, as a share of the points' w range (2nd..98th percentile).
  double tolerance_share = 0.02;
  // At least this share of the points, and this many, on the plane.
  double min_support = 0.05;
  int min_inliers = 12;
  // The plane's w over its inliers (2nd..98th percentile) spans at least this
  // share of all points' w range: a floor seen from near to far, not a wall
  // facing the camera.
  double min_slope_share = 0.2;
  // ... and continuously: no gap between consecutive inliers' w larger than
  // this share of that span. A plane through two clusters (a subject and the
  // wall behind it) has a few points of each and nothing in between.
  double max_gap_share = 0.25;
  int iterations = 500;
  unsigned seed = 1;  // RANSAC samples: the same points give the same plane
};

// The best-supported sloped plane among points (x, y, w) (normalised image
// coordinates and inverse depth in one camera), refined by least squares on
// its inliers; nothing when no plane has the support or the slope. `admit`,
// if given, must accept a plane for it to compete: a slab through a thick
// cluster of points (a subject) can gather as many points as a floor.
std::optional<InverseDepthPlane> FindSlopedPlane(
    const std::vector<Eigen::Vector3d>& xyw, const PlaneSearchOptions& options = {},
    const std::function<bool(const Eigen::Vector3d& n)>& admit = {});

}  // namespace hapcine
