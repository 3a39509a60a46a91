#pragma once
// CPU ray caster for the synthetic scene, in the camera convention of
// docs/formats.md, "Camera path specification" (OpenGL): world_from_cam maps camera
// coordinates to the world, the camera looks along its -Z axis with +Y up in
// the image, and fov_deg is the HORIZONTAL field of view.
//
// Pixel convention (the one thing every consumer must agree on):
//   * continuous image coordinates (x, y) in pixels, x to the right, y DOWN;
//   * pixel (i, j) (column i, row j) covers [i, i+1) x [j, j+1), so its centre
//     is at (i + 0.5, j + 0.5);
//   * the principal point is the image centre (W/2, H/2) in these coordinates,
//     i.e. (W/2 - 0.5, H/2 - 0.5) in OpenCV's "pixel centres are integers"
//     coordinates;
//   * focal_px = W / (2 tan(fov/2)), square pixels;
//   * the ray through (x, y) has camera-frame direction
//       ((x - W/2) / f, -(y - H/2) / f, -1).
// A pixel's value is the average of the scene over its square (supersampled
// at geometry edges, prefiltered texture elsewhere), so the centre of a small
// object lands at its projected continuous coordinate with sub-pixel accuracy.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "datasets/movers.h"
#include "datasets/scene.h"

namespace hapcine::synth {

struct CameraView {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // camera centre in the world, metres
  Eigen::Quaterniond world_from_cam = Eigen::Quaterniond::Identity();
  double fov_deg = 50;  // horizontal
  int width = 1280, height = 720;
  // Radial lens distortion (DistortNormalised below); 0 = ideal pinhole.
  double k1 = 0;
  // Independently moving objects at this view's instant (null or empty = none).
  std::shared_ptr<const MoverFrame> movers;

  double focal_px() const;
};

// One-coefficient radial distortion, in focal-normalised image coordinates
// (the model of OpenCV's k1 and COLMAP's SIMPLE_RADIAL):
//   x_n = (x - W/2) / f,  y_n = (y - H/2) / f      (ideal pinhole image, pixels x, y)
//   (x_d, y_d) = (x_n, y_n) * (1 + k1 * (x_n^2 + y_n^2))
//   distorted pixel = (W/2 + f x_d, H/2 + f y_d)
// f is focal_px of the camera path (the pinhole's), the centre is the image
// centre. k1 < 0 is barrel distortion (the corners are pulled in).
Eigen::Vector2d DistortNormalised(const Eigen::Vector2d& undistorted, double k1);
// Inverse of DistortNormalised (Newton on the radius). Exact to ~1e-12 where
// the map is monotonic: r (1 + k1 r^2) increasing, i.e. 1 + 3 k1 r^2 > 0.
Eigen::Vector2d UndistortNormalised(const Eigen::Vector2d& distorted, double k1);
// Largest distorted radius the model reaches monotonically (infinite for k1 >= 0).
double MaxDistortedRadius(double k1);

// Camera-frame ray direction (not normalised; z = -1) through the continuous
// image point (x_px, y_px).
Eigen::Vector3d CameraRayDirection(double x_px, double y_px, int width, int height,
                                   double focal_px);

// Projects a world point to continuous image coordinates (the inverse of
// CameraRayDirection; with the view's k1 distortion applied). False if the
// point is not in front of the camera.
bool ProjectToImage(const CameraView& view, const Eigen::Vector3d& world_point,
                    Eigen::Vector2d* xy_px);

struct RenderOptions {
  // Sub-samples per pixel side (N x N stratified grid); 1 = pixel centres only.
  int supersample = 2;
  // Supersample only pixels whose 4-neighbourhood sees more than one surface
  // (geometry edges). Texture detail never needs it: it is prefiltered.
  bool adaptive = true;
  // For supersample == 2: rotated-grid pattern (better on near-horizontal
  // and near-vertical edges) instead of the 2x2 square grid.
  bool rotated_grid = true;
  // Worker threads (0 = std::thread::hardware_concurrency()).
  int threads = 0;

  void Check() const;  // throws UsageError
};

// Renders one view. Returns CV_32FC3, BGR, values in [0, 255] (not clamped).
cv::Mat RenderView(const Scene& scene, const CameraView& view, const RenderOptions& options);

// Average of RenderView over `views` (motion blur across a shutter interval).
cv::Mat RenderAverage(const Scene& scene, const std::vector<CameraView>& views,
                      const RenderOptions& options);

}  // namespace hapcine::synth
