#pragma once
// Synthetic scenes for the estimator's tests: random 3-D points projected
// into cameras with known poses and focal lengths, optional pixel noise and
// outliers. Poses follow the camera-path file (OpenGL axes, world_from_cam);
// pixels follow tracks.h (top-left pixel centre at 0).

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "core/camera_path.h"
#include "core/rotation.h"
#include "extract/tracks.h"

namespace hapcine::testing {

struct SceneCamera {
  Eigen::Quaterniond world_from_cam = Eigen::Quaterniond::Identity();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double focal_px = 1000;
};

// Points in front of the identity camera (looking along -Z), depth in [near, far].
inline std::vector<Eigen::Vector3d> RandomPoints(int n, double near, double far, double spread,
                                                 unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), d(near, far);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i) {
    const double z = d(rng);
    pts.push_back(Eigen::Vector3d(u(rng) * spread * z, u(rng) * spread * z * 0.6, -z));
  }
  return pts;
}

// Pixel of world point X, or false if behind the camera / outside the image.
inline bool ProjectPx(const SceneCamera& cam, const Eigen::Vector3d& X, int width, int height,
                      Eigen::Vector2d* px) {
  const Eigen::Vector3d p = cam.world_from_cam.conjugate() * (X - cam.center);
  if (p.z() > -1e-6) return false;
  const double x = 0.5 * (width - 1) + cam.focal_px * p.x() / -p.z();
  const double y = 0.5 * (height - 1) - cam.focal_px * p.y() / -p.z();
  *px = Eigen::Vector2d(x, y);
  return x >= 0 && y >= 0 && x <= width - 1 && y <= height - 1;
}

// FrameTracks of one frame: every visible point, with noise; a fraction of
// points replaced by random positions (outliers, fixed per track).
inline FrameTracks MakeFrameTracks(int index, double fps, const SceneCamera& cam,
                                   const std::vector<Eigen::Vector3d>& pts, int width, int height,
                                   double noise_px, double outlier_fraction, std::mt19937* rng) {
  FrameTracks ft;
  ft.index = index;
  ft.time_s = index / fps;
  ft.quality = 1;
  ft.boundary = index == 0 ? ShotBoundary::kStart : ShotBoundary::kNone;
  std::normal_distribution<double> noise(0, noise_px);
  std::uniform_real_distribution<double> uni(0, 1);
  for (size_t i = 0; i < pts.size(); ++i) {
    Eigen::Vector2d px;
    if (!ProjectPx(cam, pts[i], width, height, &px)) continue;
    if (noise_px > 0) px += Eigen::Vector2d(noise(*rng), noise(*rng));
    if (static_cast<double>(i % 100) < outlier_fraction * 100)
      px = Eigen::Vector2d(uni(*rng) * width, uni(*rng) * height);
    ft.points.push_back({static_cast<long>(i), px});
  }
  return ft;
}

// Smooth 0 -> 1 ramp with eased ends over [0, n-1].
inline double Ease(int i, int n) {
  const double t = n > 1 ? static_cast<double>(i) / (n - 1) : 0;
  return 0.5 - 0.5 * std::cos(kPi * t);
}

}  // namespace hapcine::testing
