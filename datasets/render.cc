#include "datasets/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine::synth {
namespace {

using Eigen::Vector3d;

template <typename Fn>
void ParallelRows(int rows, int threads, const Fn& fn) {
  if (threads <= 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, rows);
  std::atomic<int> next{0};
  auto work = [&]() {
    for (int r; (r = next.fetch_add(1)) < rows;) fn(r);
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

struct Sampler {
  const Scene& scene;
  Eigen::Matrix3d world_from_cam;
  Vector3d center;
  int width, height;
  double f;
  double k1 = 0;
  const MoverFrame* movers = nullptr;

  // Camera-frame ray through the (distorted) image point (x, y).
  Vector3d Ray(double x, double y) const {
    if (k1 == 0) return CameraRayDirection(x, y, width, height, f);
    const Eigen::Vector2d u = UndistortNormalised(
        Eigen::Vector2d((x - 0.5 * width) / f, (y - 0.5 * height) / f), k1);
    return Vector3d(u.x(), -u.y(), -1.0);
  }

  // Colour (RGB) seen through continuous image point (x, y); `fp_scale` is
  // the sample's width in pixels (1 for a whole pixel). Sets *id.
  Rgb Sample(double x, double y, double fp_scale, int* id) const {
    const Vector3d d = world_from_cam * Ray(x, y);
    Hit hit;
    const bool scene_hit = scene.Trace(center, d, &hit);
    if (movers != nullptr) {
      Rgb albedo;
      if (movers->Trace(center, d, fp_scale / f, &hit, &albedo)) {
        *id = hit.surface_id;
        return ShadeMover(scene, hit, albedo);
      }
    }
    if (!scene_hit) {
      *id = -1;
      return Rgb::Zero();
    }
    *id = hit.surface_id;
    return scene.Shade(hit, d, hit.t * fp_scale / f);
  }
};

}  // namespace

double CameraView::focal_px() const { return FocalPxFromFovDeg(fov_deg, width); }

Vector3d CameraRayDirection(double x_px, double y_px, int width, int height, double focal_px) {
  return Vector3d((x_px - 0.5 * width) / focal_px, -(y_px - 0.5 * height) / focal_px, -1.0);
}

bool ProjectToImage(const CameraView& view, const Vector3d& world_point, Eigen::Vector2d* xy) {
  const Vector3d p = view.world_from_cam.conjugate() * (world_point - view.center);
  if (p.z() >= -1e-12) return false;
  const double f = view.focal_px();
  const double depth = -p.z();
  const Eigen::Vector2d n = DistortNormalised(Eigen::Vector2d(p.x() / depth, -p.y() / depth),
                                              view.k1);
  (*xy)[0] = 0.5 * view.width + f * n.x();
  (*xy)[1] = 0.5 * view.height + f * n.y();
  return true;
}

Eigen::Vector2d DistortNormalised(const Eigen::Vector2d& u, double k1) {
  return u * (1 + k1 * u.squaredNorm());
}

double MaxDistortedRadius(double k1) {
  if (k1 >= 0) return std::numeric_limits<double>::infinity();
  const double r = 1 / std::sqrt(-3 * k1);  // where d/dr [r (1 + k1 r^2)] = 0
  return r * (1 + k1 * r * r);
}

Eigen::Vector2d UndistortNormalised(const Eigen::Vector2d& d, double k1) {
  const double rd = d.norm();
  if (k1 == 0 || rd == 0) return d;
  double r = rd;
  for (int i = 0; i < 30; ++i) {  // Newton on g(r) = r + k1 r^3 - rd, from r = rd
    const double g = r + k1 * r * r * r - rd, dg = 1 + 3 * k1 * r * r;
    const double step = g / dg;
    r -= step;
    if (std::abs(step) < 1e-15 * (1 + r)) break;
  }
  return d * (r / rd);
}

void RenderOptions::Check() const {
  if (supersample < 1 || supersample > 8) {
    throw UsageError("supersample must be in [1, 8], got " + std::to_string(supersample));
  }
  if (threads < 0) throw UsageError("threads must be >= 0");
}

cv::Mat RenderView(const Scene& scene, const CameraView& view, const RenderOptions& options) {
  options.Check();
  if (view.width <= 0 || view.height <= 0 || !(view.fov_deg > 0 && view.fov_deg < 180)) {
    throw UsageError("bad camera view (size or fov)");
  }
  const int w = view.width, h = view.height;
  Sampler s{scene, view.world_from_cam.normalized().toRotationMatrix(), view.center, w, h,
            view.focal_px()};
  s.k1 = view.k1;
  if (view.movers && !view.movers->empty()) s.movers = view.movers.get();
  // The distortion must be invertible out to the image corner.
  const double corner_r = std::hypot(0.5 * w, 0.5 * h) / s.f;
  if (!(corner_r < MaxDistortedRadius(view.k1))) {
    throw UsageError("lens distortion k1 = " + std::to_string(view.k1) +
                     " folds the image over before its corner at this field of view");
  }
  cv::Mat out(h, w, CV_32FC3);
  const int n = options.supersample;
  // Sub-sample offsets inside the pixel square.
  std::vector<Eigen::Vector2d> offsets;
  if (n == 2 && options.rotated_grid) {
    offsets = {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
  } else {
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) offsets.emplace_back((a + 0.5) / n, (b + 0.5) / n);
    }
  }
  auto store = [&](int x, int y, const Rgb& c) {
    float* p = out.ptr<float>(y) + 3 * x;
    p[0] = c[2] * 255.0f;
    p[1] = c[1] * 255.0f;
    p[2] = c[0] * 255.0f;
  };
  auto supersampled = [&](int x, int y) {
    Rgb acc = Rgb::Zero();
    int id;
    for (const auto& o : offsets) acc += s.Sample(x + o.x(), y + o.y(), 1.0 / n, &id);
    return Rgb(acc / static_cast<float>(offsets.size()));
  };

  if (n == 1 || !options.adaptive) {
    ParallelRows(h, options.threads, [&](int y) {
      for (int x = 0; x < w; ++x) {
        int id;
        store(x, y, n == 1 ? s.Sample(x + 0.5, y + 0.5, 1.0, &id) : supersampled(x, y));
      }
    });
    return out;
  }
  // Pass 1: pixel centres, remembering which surface each one sees.
  std::vector<int> ids(static_cast<size_t>(w) * h);
  ParallelRows(h, options.threads, [&](int y) {
    for (int x = 0; x < w; ++x) {
      store(x, y, s.Sample(x + 0.5, y + 0.5, 1.0, &ids[static_cast<size_t>(y) * w + x]));
    }
  });
  // Pass 2: supersample pixels on geometry edges.
  ParallelRows(h, options.threads, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const int id = ids[static_cast<size_t>(y) * w + x];
      const bool edge = (x > 0 && ids[static_cast<size_t>(y) * w + x - 1] != id) ||
                        (x + 1 < w && ids[static_cast<size_t>(y) * w + x + 1] != id) ||
                        (y > 0 && ids[static_cast<size_t>(y - 1) * w + x] != id) ||
                        (y + 1 < h && ids[static_cast<size_t>(y + 1) * w + x] != id);
      if (edge) store(x, y, supersampled(x, y));
    }
  });
  return out;
}

cv::Mat RenderAverage(const Scene& scene, const std::vector<CameraView>& views,
                      const RenderOptions& options) {
  if (views.empty()) throw UsageError("RenderAverage: no views");
  cv::Mat acc = RenderView(scene, views[0], options);
  for (size_t i = 1; i < views.size(); ++i) acc += RenderView(scene, views[i], options);
  if (views.size() > 1) acc *= 1.0 / static_cast<double>(views.size());
  return acc;
}

}  // namespace hapcine::synth
