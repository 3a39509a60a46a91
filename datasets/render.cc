#include "datasets/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
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

  // Colour (RGB) seen through continuous image point (x, y); `fp_scale` is
  // the sample's width in pixels (1 for a whole pixel). Sets *id.
  Rgb Sample(double x, double y, double fp_scale, int* id) const {
    const Vector3d d = world_from_cam * CameraRayDirection(x, y, width, height, f);
    Hit hit;
    if (!scene.Trace(center, d, &hit)) {
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
  (*xy)[0] = 0.5 * view.width + f * p.x() / depth;
  (*xy)[1] = 0.5 * view.height - f * p.y() / depth;
  return true;
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
