#include "datasets/scene_materials.h"

#include <algorithm>
#include <cmath>

namespace hapcine::synth {
namespace {

constexpr double kPi = 3.14159265358979323846;

Rgb Lerp(const Rgb& a, const Rgb& b, float t) { return a + (b - a) * t; }

// Whole number of cells around a wrap, so periodic patterns close exactly.
int WholeCells(double wrap_m, double cell_m) {
  return std::max(1, static_cast<int>(std::lround(wrap_m / cell_m)));
}

// Random colour variation: multiply by (1 +- amount) per channel, sharing most
// of the change so hues stay plausible.
Rgb Vary(const Rgb& c, float r0, float r1, float r2, float amount) {
  const float common = (r0 - 0.5f) * 2 * amount;
  return Rgb(c[0] * (1 + common + (r1 - 0.5f) * amount * 0.5f),
             c[1] * (1 + common + (r2 - 0.5f) * amount * 0.5f),
             c[2] * (1 + common - (r1 - 0.5f) * amount * 0.5f));
}

Rgb RandomColour(uint32_t seed, int i) {
  // Saturated poster colours from a small palette, varied.
  static const Rgb kPalette[] = {{0.85f, 0.15f, 0.12f}, {0.1f, 0.3f, 0.8f},  {0.95f, 0.8f, 0.1f},
                                 {0.1f, 0.6f, 0.25f},   {0.95f, 0.95f, 0.9f}, {0.08f, 0.08f, 0.1f},
                                 {0.9f, 0.45f, 0.1f},   {0.5f, 0.15f, 0.6f}, {0.2f, 0.75f, 0.8f}};
  const int n = sizeof(kPalette) / sizeof(kPalette[0]);
  const int k = static_cast<int>(Hash01(i, 7, seed) * n) % n;
  return Vary(kPalette[k], Hash01(i, 8, seed), Hash01(i, 9, seed), Hash01(i, 10, seed), 0.2f);
}

}  // namespace

float NoiseField::operator()(double u_m, double v_m) const {
  if (wrap_u_m > 0) {
    const int cells = WholeCells(wrap_u_m, 1.0 / cells_per_m);
    return Fbm(u_m / wrap_u_m * cells, v_m * cells_per_m, octaves, seed, cells, 0);
  }
  return Fbm(u_m * cells_per_m, v_m * cells_per_m, octaves, seed);
}

Painter FlatPainter(uint32_t seed, Rgb base, float contrast) {
  NoiseField n{0.8, 2, seed};
  return [=](double u, double v) -> Rgb { return base * (1 + contrast * (2 * n(u, v) - 1)); };
}

Painter PlasterPainter(uint32_t seed, Rgb base, float contrast) {
  NoiseField coarse{1.5, 3, seed}, fine{30, 4, seed + 11};
  return [=](double u, double v) -> Rgb {
    const float c = coarse(u, v), f = fine(u, v);
    return base * (1 + contrast * (1.6f * (c - 0.5f) + 0.8f * (f - 0.5f)));
  };
}

Painter BrickPainter(uint32_t seed, Rgb brick, Rgb mortar, double bw, double bh, double m) {
  NoiseField grain{40, 3, seed + 3}, stain{0.7, 3, seed + 5}, chips{9, 2, seed + 7};
  return [=](double u, double v) -> Rgb {
    const int row = static_cast<int>(std::floor(v / bh));
    const double shift = (row & 1) ? 0.5 * bw : 0.0;
    const int col = static_cast<int>(std::floor((u + shift) / bw));
    const double lu = u + shift - col * bw, lv = v - row * bh;
    const float s = stain(u, v);
    const bool in_mortar = lu < m || lv < m;
    if (in_mortar) return mortar * (0.85f + 0.3f * grain(u, v)) * (0.8f + 0.4f * s);
    const Rgb c = Vary(brick, Hash01(col, row, seed), Hash01(col, row, seed + 1),
                       Hash01(col, row, seed + 2), 0.35f);
    const float g = grain(u, v), ch = chips(u, v);
    Rgb out = c * (0.8f + 0.35f * g) * (0.75f + 0.5f * s);
    if (ch > 0.72f) out *= 0.6f;  // dark chips: blob corners at another scale
    return out;
  };
}

Painter TilePainter(uint32_t seed, double tile_m, Rgb a, Rgb b, Rgb grout) {
  NoiseField vein{3, 4, seed + 1}, speck{60, 2, seed + 2}, stain{0.4, 3, seed + 3};
  const double g = 0.012;
  return [=](double u, double v) -> Rgb {
    const int i = static_cast<int>(std::floor(u / tile_m)), j = static_cast<int>(std::floor(v / tile_m));
    const double lu = u - i * tile_m, lv = v - j * tile_m;
    const float st = stain(u, v);
    if (lu < g || lv < g) return grout * (0.7f + 0.5f * st);
    Rgb c = ((i + j) & 1) ? a : b;
    c = Vary(c, Hash01(i, j, seed), Hash01(i, j, seed + 9), Hash01(i, j, seed + 10), 0.25f);
    // Marble veins: a turbulent sine.
    const float t = static_cast<float>(std::sin((u + v) * 9 + 12 * vein(u, v)));
    const float veins = std::pow(1 - std::abs(t), 6.0f);
    c = Lerp(c, c * 0.45f, veins);
    return c * (0.85f + 0.3f * speck(u, v)) * (0.8f + 0.4f * st);
  };
}

Painter CeilingPainter(uint32_t seed, double panel_m, Rgb panel, Rgb beam) {
  NoiseField n{8, 3, seed}, big{0.5, 2, seed + 1};
  return [=](double u, double v) -> Rgb {
    const int i = static_cast<int>(std::floor(u / panel_m)), j = static_cast<int>(std::floor(v / panel_m));
    const double lu = u - i * panel_m, lv = v - j * panel_m;
    const float k = 0.8f + 0.4f * big(u, v);
    if (lu < 0.08 || lv < 0.08) return beam * (0.8f + 0.3f * n(u, v)) * k;
    Rgb c = Vary(panel, Hash01(i, j, seed), Hash01(i, j, seed + 1), Hash01(i, j, seed + 2), 0.15f);
    // A lamp panel every few cells.
    if (Hash01(i, j, seed + 3) > 0.85f) c = Rgb(1.0f, 0.97f, 0.85f);
    return c * (0.85f + 0.25f * n(u, v)) * k;
  };
}

Painter WoodPainter(uint32_t seed, Rgb light, Rgb dark, double plank_m) {
  NoiseField warp{2, 3, seed}, fine{80, 2, seed + 1};
  return [=](double u, double v) -> Rgb {
    const int p = static_cast<int>(std::floor(v / plank_m));
    const double lv = v - p * plank_m;
    const double joint = Hash01(p, 0, seed) * 2.0;  // staggered plank ends
    const double lu = std::fmod(u + joint + 100.0, 2.0);
    if (lv < 0.006 || lu < 0.006) return dark * 0.5f;
    const float ring = static_cast<float>(
        0.5 + 0.5 * std::sin((lv * 90 + 6 * warp(u * 0.25, v) + Hash01(p, 1, seed) * 7)));
    Rgb c = Lerp(light, dark, ring * ring);
    c = Vary(c, Hash01(p, 2, seed), Hash01(p, 3, seed), Hash01(p, 4, seed), 0.2f);
    return c * (0.85f + 0.3f * fine(u, v * 0.2));
  };
}

Painter StripesPainter(uint32_t seed, const std::vector<Rgb>& palette, double mean_band_m,
                       double wrap_u_m) {
  NoiseField weave{150, 2, seed, wrap_u_m}, blot{6, 3, seed + 1, wrap_u_m};
  return [=](double u, double v) -> Rgb {
    // Bands of random width: hash the band index of a jittered lattice.
    const double x = v / mean_band_m;
    const int k = static_cast<int>(std::floor(x));
    const double boundary = 0.25 + 0.5 * Hash01(k, 0, seed);
    const int band = (x - k) < boundary ? 2 * k : 2 * k + 1;
    const Rgb c = palette[static_cast<size_t>(Hash01(band, 1, seed) * palette.size()) %
                          palette.size()];
    return c * (0.8f + 0.25f * weave(u, v) + 0.2f * (blot(u, v) - 0.5f));
  };
}

Painter ChecksPainter(uint32_t seed, Rgb a, Rgb b, double check_m, double wrap_u_m) {
  const double cu = wrap_u_m > 0 ? wrap_u_m / (2 * WholeCells(wrap_u_m, 2 * check_m)) : check_m;
  NoiseField weave{150, 2, seed, wrap_u_m};
  return [=](double u, double v) -> Rgb {
    const int i = static_cast<int>(std::floor(u / cu)), j = static_cast<int>(std::floor(v / check_m));
    const double lu = u / cu - i, lv = v / check_m - j;
    Rgb c = ((i + j) & 1) ? a : b;
    if (lu < 0.12 || lv < 0.12) c = Lerp(c, Rgb(0.95f, 0.9f, 0.8f), 0.7f);  // thin light lines
    return c * (0.8f + 0.3f * weave(u, v));
  };
}

Painter NoisyPainter(uint32_t seed, Rgb base, float contrast, double cells_per_m,
                     double wrap_u_m) {
  NoiseField n{cells_per_m, 5, seed, wrap_u_m};
  return [=](double u, double v) -> Rgb {
    const float x = n(u, v);
    return base * (1 + contrast * 2.2f * (x - 0.5f));
  };
}

Painter FlutedPainter(uint32_t seed, Rgb base, double flute_m, double wrap_u_m) {
  const int flutes = WholeCells(wrap_u_m, flute_m);
  NoiseField marble{5, 5, seed, wrap_u_m};
  return [=](double u, double v) -> Rgb {
    const double ph = u / wrap_u_m * flutes;
    const double f = ph - std::floor(ph);
    const float groove = f < 0.15 ? 0.6f : 1.0f;
    const float m = marble(u, v);
    const float vein = std::pow(1 - std::abs(static_cast<float>(std::sin(v * 3 + 10 * m))), 8.0f);
    // Ring mouldings every 1.2 m.
    const double ring = std::fmod(v, 1.2);
    const float band = ring < 0.05 ? 0.65f : 1.0f;
    return base * groove * band * (0.85f + 0.3f * m) * (1 - 0.5f * vein);
  };
}

std::vector<Poster> RandomPosters(uint32_t seed, int count, double u0, double u1, double v0,
                                  double v1, double min_size, double max_size) {
  std::vector<Poster> out;
  for (int attempt = 0; attempt < count * 40 && static_cast<int>(out.size()) < count; ++attempt) {
    const double w = min_size + (max_size - min_size) * Hash01(attempt, 0, seed);
    const double h = w * (0.7 + 0.7 * Hash01(attempt, 1, seed));
    if (w > u1 - u0 || h > v1 - v0) continue;
    const double pu = u0 + (u1 - u0 - w) * Hash01(attempt, 2, seed);
    const double pv = v0 + (v1 - v0 - h) * Hash01(attempt, 3, seed);
    bool overlaps = false;
    for (const Poster& p : out) {
      if (pu < p.u1 + 0.3 && pu + w > p.u0 - 0.3 && pv < p.v1 + 0.3 && pv + h > p.v0 - 0.3) {
        overlaps = true;
      }
    }
    if (overlaps) continue;
    Poster p{pu, pv, pu + w, pv + h, RandomColour(seed + 1, attempt),
             Rgb(0.12f, 0.1f, 0.08f), {}};
    const int n = 6 + static_cast<int>(Hash01(attempt, 4, seed) * 14);
    for (int s = 0; s < n; ++s) {
      Poster::Shape sh;
      sh.kind = static_cast<int>(Hash01(attempt * 64 + s, 5, seed) * 5) % 5;
      sh.cu = pu + w * (0.1 + 0.8 * Hash01(attempt * 64 + s, 6, seed));
      sh.cv = pv + h * (0.1 + 0.8 * Hash01(attempt * 64 + s, 7, seed));
      // Sizes spread over a decade: corners at many scales.
      sh.size = std::min(w, h) * 0.04 * std::pow(10.0, Hash01(attempt * 64 + s, 8, seed));
      sh.angle = kPi * Hash01(attempt * 64 + s, 9, seed);
      sh.colour = RandomColour(seed + 2, attempt * 64 + s);
      p.shapes.push_back(sh);
    }
    out.push_back(std::move(p));
  }
  return out;
}

Painter WithPosters(Painter base, std::vector<Poster> posters) {
  return [base = std::move(base), posters = std::move(posters)](double u, double v) -> Rgb {
    for (const Poster& p : posters) {
      if (u < p.u0 || u > p.u1 || v < p.v0 || v > p.v1) continue;
      const double edge = std::min({u - p.u0, p.u1 - u, v - p.v0, p.v1 - v});
      if (edge < 0.03) return p.frame;
      Rgb c = p.background;
      for (const Poster::Shape& s : p.shapes) {  // later shapes on top
        const double du = u - s.cu, dv = v - s.cv;
        const double ca = std::cos(s.angle), sa = std::sin(s.angle);
        const double x = ca * du + sa * dv, y = -sa * du + ca * dv;
        bool in = false;
        switch (s.kind) {
          case 0: in = x * x + y * y < s.size * s.size; break;
          case 1: in = std::abs(x) < s.size && std::abs(y) < 0.6 * s.size; break;
          case 2: in = y > -0.5 * s.size && std::abs(x) < (s.size - y) * 0.6 && y < s.size; break;
          case 3: {
            const double r2 = x * x + y * y;
            in = r2 < s.size * s.size && r2 > 0.36 * s.size * s.size;
            break;
          }
          default:
            in = std::abs(x) < s.size && std::abs(y) < s.size &&
                 std::fmod(y + 10 * s.size, 0.4 * s.size) < 0.2 * s.size;
        }
        if (in) c = s.colour;
      }
      return c;
    }
    return base(u, v);
  };
}

}  // namespace hapcine::synth
