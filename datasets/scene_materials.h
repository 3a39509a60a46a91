#pragma once
// Procedural surface patterns ("painters") for the synthetic hall. Each
// returns a colour for a surface position in metres and is baked into a
// mipmapped Texture once per scene. The patterns are chosen for trackers:
// corners at many scales (bricks, tiles, planks, poster shapes) over
// multi-octave noise, so that any image patch, at any zoom, has texture.
//
// `wrap_u_m` > 0 makes a pattern periodic in u with that period (for surfaces
// that close on themselves: cylinders, spheres), so there is no seam.

#include <cstdint>
#include <vector>

#include "datasets/scene_texture.h"

namespace hapcine::synth {

// Multi-octave value noise with a base frequency in cells per metre.
struct NoiseField {
  double cells_per_m = 4;
  int octaves = 4;
  uint32_t seed = 1;
  double wrap_u_m = 0;
  float operator()(double u_m, double v_m) const;
};

Painter FlatPainter(uint32_t seed, Rgb base, float contrast);
Painter PlasterPainter(uint32_t seed, Rgb base, float contrast);
Painter BrickPainter(uint32_t seed, Rgb brick, Rgb mortar, double brick_w_m, double brick_h_m,
                     double mortar_m);
Painter TilePainter(uint32_t seed, double tile_m, Rgb a, Rgb b, Rgb grout);
Painter CeilingPainter(uint32_t seed, double panel_m, Rgb panel, Rgb beam);
Painter WoodPainter(uint32_t seed, Rgb light, Rgb dark, double plank_m);
// Horizontal bands of random widths and colours from `palette`, with noise.
Painter StripesPainter(uint32_t seed, const std::vector<Rgb>& palette, double mean_band_m,
                       double wrap_u_m);
// Tartan-like checks; the count around the wrap is made whole.
Painter ChecksPainter(uint32_t seed, Rgb a, Rgb b, double check_m, double wrap_u_m);
// Coarse woven noise (denim, skin, hair, marble) in one colour family.
Painter NoisyPainter(uint32_t seed, Rgb base, float contrast, double cells_per_m,
                     double wrap_u_m);
// Vertical flutes (pillars): whole number of flutes around wrap_u_m.
Painter FlutedPainter(uint32_t seed, Rgb base, double flute_m, double wrap_u_m);

// A rectangle on a wall filled with random shapes (a poster or a painting).
struct Poster {
  double u0, v0, u1, v1;  // extent in metres
  Rgb background, frame;
  struct Shape {
    int kind;  // 0 disc, 1 rectangle, 2 triangle, 3 ring, 4 bars
    double cu, cv, size, angle;
    Rgb colour;
  };
  std::vector<Shape> shapes;
};
// `count` posters spread over [u0,u1] x [v0,v1] without overlapping.
std::vector<Poster> RandomPosters(uint32_t seed, int count, double u0, double u1, double v0,
                                  double v1, double min_size_m, double max_size_m);
// Paints `posters` over `base`.
Painter WithPosters(Painter base, std::vector<Poster> posters);

}  // namespace hapcine::synth
