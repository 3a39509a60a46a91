#include "datasets/movers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include "datasets/scene_materials.h"

namespace hapcine::synth {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = 1e-9;

// Texture slots of MoverFrame::textures.
enum Tex { kSkin, kHair, kEye, kLips, kClothA, kClothB, kClothC, kDenim, kTexCount };

// Skin with freckles and blotches at a few scales, so a face has corners to
// track (a flat skin colour would be untrackable and test nothing).
Painter SkinPainter(uint32_t seed) {
  const NoiseField coarse{18, 4, seed, 0}, fine{90, 2, seed + 7, 0};
  return [=](double u, double v) -> Rgb {
    const float a = coarse(u, v), b = fine(u, v);
    const float spot = b > 0.68f ? 0.55f : 1.0f;  // freckles
    const float shade = 0.75f + 0.5f * (a - 0.5f);
    return Rgb(0.86f, 0.64f, 0.52f) * shade * spot;
  };
}

std::shared_ptr<const std::vector<std::shared_ptr<const Texture>>> PaintTextures(uint32_t seed) {
  auto tex = std::make_shared<std::vector<std::shared_ptr<const Texture>>>(kTexCount);
  auto paint = [&](int slot, const Painter& p, double w_m, double h_m, double texel_m) {
    (*tex)[slot] = std::make_shared<Texture>(p, w_m, h_m, texel_m, /*wrap=*/true, 1);
  };
  const uint32_t s = seed * 2654435761U + 17;
  paint(kSkin, SkinPainter(s + 1), 0.66, 0.42, 0.002);
  paint(kHair, NoisyPainter(s + 2, Rgb(0.22f, 0.14f, 0.08f), 0.8f, 60, 0.66), 0.66, 0.32, 0.002);
  paint(kEye, NoisyPainter(s + 3, Rgb(0.12f, 0.1f, 0.1f), 0.6f, 200, 0.1), 0.1, 0.04, 0.0005);
  paint(kLips, NoisyPainter(s + 4, Rgb(0.55f, 0.18f, 0.18f), 0.5f, 150, 0.16), 0.16, 0.04, 0.001);
  paint(kClothA,
        StripesPainter(s + 5, {{0.8f, 0.2f, 0.15f}, {0.95f, 0.9f, 0.8f}, {0.15f, 0.2f, 0.5f}},
                       0.05, 1.5),
        1.5, 1.0, 0.004);
  paint(kClothB, ChecksPainter(s + 6, Rgb(0.2f, 0.45f, 0.25f), Rgb(0.9f, 0.85f, 0.4f), 0.06, 1.5),
        1.5, 1.0, 0.004);
  paint(kClothC,
        StripesPainter(s + 7, {{0.3f, 0.3f, 0.35f}, {0.9f, 0.6f, 0.2f}, {0.6f, 0.1f, 0.5f}}, 0.08,
                       1.5),
        1.5, 1.0, 0.004);
  paint(kDenim, NoisyPainter(s + 8, Rgb(0.2f, 0.28f, 0.5f), 0.7f, 40, 0.6), 0.6, 0.9, 0.004);
  return tex;
}

std::shared_ptr<const std::vector<std::shared_ptr<const Texture>>> MoverTextures(uint32_t seed) {
  static std::mutex mutex;
  static std::map<uint32_t, std::shared_ptr<const std::vector<std::shared_ptr<const Texture>>>>
      cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[seed];
  if (!slot) slot = PaintTextures(seed);
  return slot;
}

Matrix3d RotY(double deg) { return Eigen::AngleAxisd(deg * kPi / 180, Vector3d::UnitY()).matrix(); }
Matrix3d RotX(double deg) { return Eigen::AngleAxisd(deg * kPi / 180, Vector3d::UnitX()).matrix(); }

// Adds a part given in a parent frame (parent_from_local rotation R, origin o).
void AddPart(MoverFrame* f, const Matrix3d& R, const Vector3d& o, const Vector3d& local_center,
             const Matrix3d& local_rot, const Vector3d& radii, int texture) {
  MoverEllipsoid e;
  e.center = o + R * local_center;
  e.world_from_local = R * local_rot;
  e.radii = radii;
  e.texture = texture;
  f->parts.push_back(e);
}

double Hash(int a, int b, uint32_t seed) { return Hash01(a, b, seed); }

// A smooth periodic signal: two sinusoids with seeded phases.
double Wave(double t, double period_s, uint32_t seed, int channel) {
  const double p1 = 2 * kPi * Hash(channel, 1, seed), p2 = 2 * kPi * Hash(channel, 2, seed);
  return 0.75 * std::sin(2 * kPi * t / period_s + p1) +
         0.25 * std::sin(2 * kPi * t / (0.43 * period_s) + p2);
}

// Head and shoulders: the head turns (yaw up to ~27 deg) and nods (~11 deg)
// about the neck, the body sways, the eyes blink every ~2.3 s and the mouth
// opens and closes as in speech. +Z of the body faces the camera.
void AddHead(MoverFrame* f, double t, uint32_t seed) {
  const Vector3d head = MoverHeadCenter();
  const Vector3d sway(0.012 * Wave(t, 4.1, seed, 10), 0.004 * Wave(t, 3.3, seed, 11), 0);
  const Matrix3d body_rot = RotY(4 * Wave(t, 5.3, seed, 12));
  const Vector3d neck = head + sway + Vector3d(0, -0.11, 0);
  AddPart(f, body_rot, neck, {0, -0.22, -0.02}, Matrix3d::Identity(), {0.23, 0.2, 0.12}, kClothA);
  AddPart(f, body_rot, neck, {0, -0.03, -0.01}, Matrix3d::Identity(), {0.05, 0.08, 0.05}, kSkin);
  const Matrix3d head_rot = body_rot * RotY(22 * Wave(t, 3.1, seed, 13)) *
                            RotX(8 * Wave(t, 1.7, seed, 14));
  const Vector3d pivot = neck;  // the head turns about the top of the neck
  const Vector3d c(0, 0.11, 0);  // head centre above the pivot
  const Matrix3d I = Matrix3d::Identity();
  AddPart(f, head_rot, pivot, c, I, {0.095, 0.125, 0.105}, kSkin);
  AddPart(f, head_rot, pivot, c + Vector3d(0, 0.04, -0.012), I, {0.1, 0.1, 0.105}, kHair);
  AddPart(f, head_rot, pivot, c + Vector3d(0, -0.005, 0.1), I, {0.012, 0.022, 0.015}, kSkin);
  // Blink: the eyes close for 0.15 s every 2.3 s (seeded phase).
  const double blink_phase = std::fmod(t + 2.3 * Hash(15, 0, seed), 2.3);
  const double open = blink_phase < 0.15 ? 0.12 : 1.0;
  for (int side : {-1, 1}) {
    AddPart(f, head_rot, pivot, c + Vector3d(side * 0.035, 0.025, 0.092), I,
            {0.016, 0.011 * open, 0.008}, kEye);
  }
  const double talk = 0.5 + 0.5 * std::sin(2 * kPi * 3.3 * t) * std::max(0.0, Wave(t, 2.9, seed, 16));
  AddPart(f, head_rot, pivot, c + Vector3d(0, -0.06, 0.088), I, {0.025, 0.004 + 0.009 * talk, 0.007},
          kLips);
}

// A walker with its feet at `feet`, walking along heading `yaw_deg` (0 = +Z),
// `phase` the gait phase (radians). Legs and arms swing +-25 deg, the body
// bobs 2.5 cm twice per stride.
void AddWalker(MoverFrame* f, const Vector3d& feet, double yaw_deg, double phase, int cloth,
               double height_scale) {
  const Matrix3d R = RotY(yaw_deg);
  const double k = height_scale;
  const Vector3d o = feet + Vector3d(0, 0.025 * k * std::cos(2 * phase), 0);
  const Matrix3d I = Matrix3d::Identity();
  AddPart(f, R, o, k * Vector3d(0, 1.2, 0), I, k * Vector3d(0.19, 0.3, 0.12), cloth);
  AddPart(f, R, o, k * Vector3d(0, 1.65, 0), I, k * Vector3d(0.09, 0.115, 0.1), kSkin);
  AddPart(f, R, o, k * Vector3d(0, 1.69, -0.01), I, k * Vector3d(0.095, 0.09, 0.1), kHair);
  const double swing = 25 * std::sin(phase);
  for (int side : {-1, 1}) {
    const Matrix3d leg = RotX(side * swing);
    AddPart(f, R, o + R * (k * Vector3d(side * 0.09, 0.88, 0)), leg * (k * Vector3d(0, -0.43, 0)),
            leg, k * Vector3d(0.075, 0.43, 0.08), kDenim);
    const Matrix3d arm = RotX(-side * swing * 0.8);
    AddPart(f, R, o + R * (k * Vector3d(side * 0.24, 1.42, 0)), arm * (k * Vector3d(0, -0.3, 0)),
            arm, k * Vector3d(0.05, 0.31, 0.05), cloth);
  }
}

struct Walk {
  double x0, z0, x1, z1;  // start and end of the walk, metres
  double s0, s1;          // fraction of the clip when it starts and ends
  int cloth;
  double height_scale;
};

void AddWalk(MoverFrame* f, const Walk& w, double t, double duration_s) {
  const double s = std::clamp((t / duration_s - w.s0) / (w.s1 - w.s0), 0.0, 1.0);
  const Vector3d a(w.x0, 0, w.z0), b(w.x1, 0, w.z1);
  const Vector3d feet = a + s * (b - a);
  const double yaw = std::atan2(b.x() - a.x(), b.z() - a.z()) * 180 / kPi;
  // Gait: one stride (two steps) per 1.4 m walked.
  const double walked = s * (b - a).norm();
  AddWalker(f, feet, yaw, 2 * kPi * walked / 1.4, w.cloth, w.height_scale);
}

std::vector<Walk> Walks(MoverKind kind, uint32_t seed) {
  if (kind == MoverKind::kCrossing) {
    return {{-5.0, -2.6, 5.0, -2.6, 0.0, 1.0, kClothA, 1.0},
            {5.0, -3.4, -5.0, -3.4, 0.05, 0.95, kClothB, 0.95},
            {-5.0, -0.9, 5.0, -0.9, 0.25, 0.85, kClothC, 1.05}};
  }
  if (kind == MoverKind::kFarWalkers) {
    return {{-6.0, -8.0, 6.0, -8.0, 0.0, 1.0, kClothB, 1.0},
            {6.0, -9.5, -6.0, -9.5, 0.1, 0.9, kClothA, 1.0}};
  }
  std::vector<Walk> crowd;
  if (kind != MoverKind::kCrowd) return crowd;
  for (int i = 0; i < 14; ++i) {
    const double x = -5.5 + 11 * Hash(i, 20, seed), z = -8.5 + 6 * Hash(i, 21, seed);
    // Mostly sideways (across the view), 4-8 m over the clip.
    const double dir = (Hash(i, 22, seed) < 0.5 ? -1 : 1);
    const double len = 4 + 4 * Hash(i, 23, seed), dz = 2 * (Hash(i, 24, seed) - 0.5);
    crowd.push_back({x, z, x + dir * len, z + dz, 0, 1, kClothA + i % 3,
                     0.9 + 0.2 * Hash(i, 25, seed)});
  }
  return crowd;
}

// Ray against one ellipsoid: nearest t in (kEps, t_max); local unit-sphere
// point in *unit.
bool TraceEllipsoid(const MoverEllipsoid& e, const Vector3d& o, const Vector3d& d, double t_max,
                    double* t, Vector3d* unit) {
  const Matrix3d Rt = e.world_from_local.transpose();
  const Vector3d lo = (Rt * (o - e.center)).cwiseQuotient(e.radii);
  const Vector3d ld = (Rt * d).cwiseQuotient(e.radii);
  const double a = ld.squaredNorm(), b = lo.dot(ld), c = lo.squaredNorm() - 1;
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  const double sq = std::sqrt(disc);
  double tt = (-b - sq) / a;
  if (tt <= kEps) tt = (-b + sq) / a;
  if (tt <= kEps || tt >= t_max) return false;
  *t = tt;
  *unit = lo + tt * ld;
  return true;
}

// Groups parts [begin, end) under one bounding sphere.
void CloseGroup(MoverFrame* f, int begin) {
  MoverGroup g;
  g.begin = begin;
  g.end = static_cast<int>(f->parts.size());
  Vector3d c = Vector3d::Zero();
  for (int i = g.begin; i < g.end; ++i) c += f->parts[i].center;
  g.center = c / std::max(1, g.end - g.begin);
  g.radius = 0;
  for (int i = g.begin; i < g.end; ++i) {
    const MoverEllipsoid& e = f->parts[i];
    g.radius = std::max(g.radius, (e.center - g.center).norm() + e.radii.maxCoeff());
  }
  f->groups.push_back(g);
}

}  // namespace

Vector3d MoverHeadCenter() { return Vector3d(0.08, 1.57, -0.3); }

bool MoverFrame::Trace(const Vector3d& o, const Vector3d& d, double footprint_per_t, Hit* hit,
                       Rgb* albedo) const {
  int best = -1;
  double best_t = hit->surface_id >= 0 ? hit->t : std::numeric_limits<double>::infinity();
  Vector3d best_unit;
  const double dd = d.squaredNorm();
  for (const MoverGroup& g : groups) {
    // Skip the group when the ray misses its bounding sphere.
    const Vector3d oc = g.center - o;
    const double along = oc.dot(d) / dd;
    if ((oc - along * d).squaredNorm() > g.radius * g.radius) continue;
    for (int i = g.begin; i < g.end; ++i) {
      double t;
      Vector3d unit;
      if (TraceEllipsoid(parts[i], o, d, best_t, &t, &unit)) {
        best = i;
        best_t = t;
        best_unit = unit;
      }
    }
  }
  if (best < 0) return false;
  const MoverEllipsoid& e = parts[best];
  hit->t = best_t;
  hit->surface_id = kMoverSurfaceBase + best;
  hit->texture = -1;
  hit->room_face = -1;
  hit->p = o + best_t * d;
  hit->n = (e.world_from_local * best_unit.cwiseQuotient(e.radii)).normalized();
  if (hit->n.dot(d) > 0) hit->n = -hit->n;
  // Longitude from the local -Z side (the seam, at the back) and colatitude
  // from +Y, scaled to the texture's size so the wrap is seamless.
  const Texture& tex = *(*textures)[e.texture];
  const double lon = std::atan2(best_unit.x(), best_unit.z());  // 0 in front, +-pi at the back
  const double colat = std::acos(std::clamp(best_unit.y(), -1.0, 1.0));
  hit->u_m = (lon / (2 * kPi) + 0.5) * tex.width_m();
  hit->v_m = colat / kPi * tex.height_m();
  *albedo = tex.SampleTrilinear(hit->u_m, hit->v_m, best_t * footprint_per_t);
  return true;
}

MoverFrame MoversAt(MoverKind kind, double t, double duration_s, uint32_t seed) {
  MoverFrame f;
  if (kind == MoverKind::kNone) return f;
  f.textures = MoverTextures(seed);
  if (kind == MoverKind::kHead) {
    AddHead(&f, t, seed);
    CloseGroup(&f, 0);
    return f;
  }
  for (const Walk& w : Walks(kind, seed)) {
    const int begin = static_cast<int>(f.parts.size());
    AddWalk(&f, w, t, duration_s);
    CloseGroup(&f, begin);
  }
  return f;
}

Rgb ShadeMover(const Scene& scene, const Hit& hit, const Rgb& albedo) {
  float light = scene.ambient;
  for (const PointLight& l : scene.lights) {
    const Vector3d to = l.pos - hit.p;
    const double dist2 = to.squaredNorm();
    const double ndl = hit.n.dot(to) / std::sqrt(dist2);
    if (ndl <= 0) continue;
    light += static_cast<float>(l.intensity * ndl / (1 + dist2 / (l.falloff_m * l.falloff_m)));
  }
  return albedo * light;
}

}  // namespace hapcine::synth
