#pragma once
// Procedural, band-limited textures for the synthetic scene.
//
// A texture is painted once, at build time, by a "painter" (a function of the
// surface position in metres) into a texel grid and reduced to a mipmap
// pyramid. The renderer then samples it with a filter as wide as the pixel's
// footprint on the surface (trilinear mipmapping, plus a few taps along the
// stretched axis at grazing angles), so the pictures carry no frequencies
// above the pixel grid's Nyquist limit and nothing shimmers when the camera
// moves. Each texel is itself painted with 2x2 supersampling so that the sharp
// edges of bricks, tiles and posters are antialiased in the texture.
//
// Nothing here is downloaded: all patterns come from hash-based value noise and
// simple shapes, driven by a seed, so the same seed gives the same pixels.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

namespace hapcine::synth {

using Rgb = Eigen::Vector3f;  // linear-ish display values in [0, 1], R G B

// Hash-based lattice value noise in [0, 1]. When period_x/period_y > 0 the
// lattice wraps with that period (in lattice cells) so the noise tiles.
float ValueNoise(double x, double y, uint32_t seed, int period_x = 0, int period_y = 0);
// Fractal sum of `octaves` value-noise layers (gain 0.5, lacunarity 2), in
// about [0, 1]. Periods double with each octave so tiling is preserved.
float Fbm(double x, double y, int octaves, uint32_t seed, int period_x = 0, int period_y = 0);
// Uniform hash of integer coordinates in [0, 1).
float Hash01(int x, int y, uint32_t seed);

// A painter returns the colour at surface position (u_m, v_m), in metres.
using Painter = std::function<Rgb(double u_m, double v_m)>;

class Texture {
 public:
  // Paints a texture covering width_m x height_m with square texels of
  // texel_m (the grid is rounded up to whole texels). `wrap` makes lookups
  // repeat (for surfaces that go round, like cylinders); otherwise they clamp.
  // Painting runs on `threads` threads (0 = all cores).
  Texture(const Painter& painter, double width_m, double height_m, double texel_m, bool wrap,
          int threads = 0);

  // Filtered lookup. `footprint_m` is the pixel's footprint along its shorter
  // axis, `aniso_ratio` >= 1 the longer/shorter ratio and (dir_u, dir_v) the
  // unit direction of the longer axis in (u, v).
  Rgb Sample(double u_m, double v_m, double footprint_m, double aniso_ratio, double dir_u,
             double dir_v) const;
  // Trilinear lookup with an isotropic footprint.
  Rgb SampleTrilinear(double u_m, double v_m, double footprint_m) const;

  double width_m() const { return width_m_; }
  double height_m() const { return height_m_; }
  int levels() const { return static_cast<int>(levels_.size()); }
  int width_px(int level = 0) const { return levels_[level].w; }
  int height_px(int level = 0) const { return levels_[level].h; }
  // Unfiltered texel of a level (for tests).
  Rgb Texel(int level, int x, int y) const;

 private:
  struct Level {
    int w = 0, h = 0;
    double px_per_m_u = 0, px_per_m_v = 0;
    std::vector<uint8_t> rgba;  // w*h*4, row-major
  };
  Rgb Bilinear(const Level& l, double u_m, double v_m) const;

  std::vector<Level> levels_;
  double width_m_ = 0, height_m_ = 0, texel_m_ = 0;
  bool wrap_ = false;
};

}  // namespace hapcine::synth
