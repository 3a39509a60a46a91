#include "datasets/scene_texture.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace hapcine::synth {
namespace {

inline uint32_t Mix(uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352dU;
  h ^= h >> 15;
  h *= 0x846ca68bU;
  h ^= h >> 16;
  return h;
}

inline int Wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

inline double Quintic(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

inline uint8_t ToByte(float v) {
  return static_cast<uint8_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

}  // namespace

float Hash01(int x, int y, uint32_t seed) {
  const uint32_t h = Mix(static_cast<uint32_t>(x) * 0x9E3779B1U ^
                         Mix(static_cast<uint32_t>(y) * 0x85EBCA77U ^ Mix(seed + 0x27d4eb2fU)));
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

float ValueNoise(double x, double y, uint32_t seed, int period_x, int period_y) {
  const double fx = std::floor(x), fy = std::floor(y);
  int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  int x1 = x0 + 1, y1 = y0 + 1;
  if (period_x > 0) {
    x0 = Wrap(x0, period_x);
    x1 = Wrap(x1, period_x);
  }
  if (period_y > 0) {
    y0 = Wrap(y0, period_y);
    y1 = Wrap(y1, period_y);
  }
  const double tx = Quintic(x - fx), ty = Quintic(y - fy);
  const double a = Hash01(x0, y0, seed), b = Hash01(x1, y0, seed);
  const double c = Hash01(x0, y1, seed), d = Hash01(x1, y1, seed);
  const double top = a + (b - a) * tx, bottom = c + (d - c) * tx;
  return static_cast<float>(top + (bottom - top) * ty);
}

float Fbm(double x, double y, int octaves, uint32_t seed, int period_x, int period_y) {
  double sum = 0, amp = 0.5, norm = 0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * ValueNoise(x, y, seed + 977U * o, period_x, period_y);
    norm += amp;
    x *= 2;
    y *= 2;
    period_x *= 2;
    period_y *= 2;
    amp *= 0.5;
  }
  return static_cast<float>(sum / norm);
}

Texture::Texture(const Painter& painter, double width_m, double height_m, double texel_m,
                 bool wrap, int threads)
    : width_m_(width_m), height_m_(height_m), texel_m_(texel_m), wrap_(wrap) {
  Level base;
  base.w = std::max(1, static_cast<int>(std::ceil(width_m / texel_m - 1e-9)));
  base.h = std::max(1, static_cast<int>(std::ceil(height_m / texel_m - 1e-9)));
  base.px_per_m_u = base.w / width_m;
  base.px_per_m_v = base.h / height_m;
  base.rgba.assign(static_cast<size_t>(base.w) * base.h * 4, 255);
  if (threads <= 0) threads = std::max(1u, std::thread::hardware_concurrency());
  // Paint with a 2x2 box-filtered supersample per texel: texel (x, y) covers
  // [x, x+1) / px_per_m, so its samples sit at quarter offsets.
  std::atomic<int> next_row{0};
  auto work = [&]() {
    for (int y; (y = next_row.fetch_add(1)) < base.h;) {
      for (int x = 0; x < base.w; ++x) {
        Rgb acc = Rgb::Zero();
        for (int sy = 0; sy < 2; ++sy) {
          for (int sx = 0; sx < 2; ++sx) {
            acc += painter((x + 0.25 + 0.5 * sx) / base.px_per_m_u,
                           (y + 0.25 + 0.5 * sy) / base.px_per_m_v);
          }
        }
        acc *= 0.25f;
        uint8_t* p = &base.rgba[(static_cast<size_t>(y) * base.w + x) * 4];
        p[0] = ToByte(acc[0]);
        p[1] = ToByte(acc[1]);
        p[2] = ToByte(acc[2]);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  levels_.push_back(std::move(base));

  // Mipmaps: 2x2 box filter (clamped at odd edges). Each level keeps its own
  // texels-per-metre so that odd sizes stay exactly registered.
  while (levels_.back().w > 1 || levels_.back().h > 1) {
    const Level& p = levels_.back();
    Level l;
    l.w = std::max(1, (p.w + 1) / 2);
    l.h = std::max(1, (p.h + 1) / 2);
    l.px_per_m_u = l.w / width_m;
    l.px_per_m_v = l.h / height_m;
    l.rgba.resize(static_cast<size_t>(l.w) * l.h * 4);
    for (int y = 0; y < l.h; ++y) {
      for (int x = 0; x < l.w; ++x) {
        for (int c = 0; c < 4; ++c) {
          int sum = 0;
          for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
              const int sx = std::min(2 * x + dx, p.w - 1), sy = std::min(2 * y + dy, p.h - 1);
              sum += p.rgba[(static_cast<size_t>(sy) * p.w + sx) * 4 + c];
            }
          }
          l.rgba[(static_cast<size_t>(y) * l.w + x) * 4 + c] = static_cast<uint8_t>((sum + 2) / 4);
        }
      }
    }
    levels_.push_back(std::move(l));
  }
}

Rgb Texture::Texel(int level, int x, int y) const {
  const Level& l = levels_[level];
  const uint8_t* p = &l.rgba[(static_cast<size_t>(y) * l.w + x) * 4];
  return Rgb(p[0], p[1], p[2]) * (1.0f / 255.0f);
}

Rgb Texture::Bilinear(const Level& l, double u_m, double v_m) const {
  // Texel centres sit at (i + 0.5) / px_per_m.
  const double x = u_m * l.px_per_m_u - 0.5, y = v_m * l.px_per_m_v - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy), x1 = x0 + 1, y1 = y0 + 1;
  if (wrap_) {
    x0 = Wrap(x0, l.w);
    x1 = Wrap(x1, l.w);
    y0 = Wrap(y0, l.h);
    y1 = Wrap(y1, l.h);
  } else {
    x0 = std::clamp(x0, 0, l.w - 1);
    x1 = std::clamp(x1, 0, l.w - 1);
    y0 = std::clamp(y0, 0, l.h - 1);
    y1 = std::clamp(y1, 0, l.h - 1);
  }
  const uint8_t* a = &l.rgba[(static_cast<size_t>(y0) * l.w + x0) * 4];
  const uint8_t* b = &l.rgba[(static_cast<size_t>(y0) * l.w + x1) * 4];
  const uint8_t* c = &l.rgba[(static_cast<size_t>(y1) * l.w + x0) * 4];
  const uint8_t* d = &l.rgba[(static_cast<size_t>(y1) * l.w + x1) * 4];
  const float wa = (1 - tx) * (1 - ty), wb = tx * (1 - ty), wc = (1 - tx) * ty, wd = tx * ty;
  constexpr float k = 1.0f / 255.0f;
  return Rgb((wa * a[0] + wb * b[0] + wc * c[0] + wd * d[0]) * k,
             (wa * a[1] + wb * b[1] + wc * c[1] + wd * d[1]) * k,
             (wa * a[2] + wb * b[2] + wc * c[2] + wd * d[2]) * k);
}

Rgb Texture::SampleTrilinear(double u_m, double v_m, double footprint_m) const {
  const double lod = std::log2(std::max(footprint_m / texel_m_, 1e-6));
  const int last = levels() - 1;
  if (lod <= 0) return Bilinear(levels_[0], u_m, v_m);
  if (lod >= last) return Bilinear(levels_[last], u_m, v_m);
  const int l0 = static_cast<int>(lod);
  const float t = static_cast<float>(lod - l0);
  const Rgb a = Bilinear(levels_[l0], u_m, v_m);
  if (t < 1e-3f) return a;
  return a + (Bilinear(levels_[l0 + 1], u_m, v_m) - a) * t;
}

Rgb Texture::Sample(double u_m, double v_m, double footprint_m, double aniso_ratio, double dir_u,
                    double dir_v) const {
  if (aniso_ratio <= 1.5) return SampleTrilinear(u_m, v_m, footprint_m * aniso_ratio);
  // Up to 4 trilinear taps spread along the long axis, each filtering its
  // share of the footprint: cheap anisotropic filtering that keeps grazing
  // floors sharp across and unaliased along the view direction.
  const int taps = std::min(4, static_cast<int>(std::ceil(aniso_ratio)));
  const double major = footprint_m * aniso_ratio;
  const double tap_fp = std::max(footprint_m, major / taps);
  Rgb acc = Rgb::Zero();
  for (int i = 0; i < taps; ++i) {
    const double s = ((i + 0.5) / taps - 0.5) * major;
    acc += SampleTrilinear(u_m + s * dir_u, v_m + s * dir_v, tap_fp);
  }
  return acc / static_cast<float>(taps);
}

}  // namespace hapcine::synth
