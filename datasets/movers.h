#pragma once
// Independently moving and deforming objects ("movers") for the synthetic
// clips: a head that turns, nods and blinks, walkers that cross the frame, a
// crowd. They are NOT part of the camera's ground truth: the camera path of a
// clip is the camera's only, and every mover is content the estimator must
// ignore.
//
// A mover is a set of rotated, textured ellipsoids whose pose and radii are
// closed-form functions of time, so a frame (or a sub-frame inside a shutter
// interval) is rendered exactly. Their textures are painted in the object's
// own coordinates, so they move with it (trackable, like skin and clothes).
// The renderer (render.cc) traces them after the static scene and keeps the
// nearer hit; shading uses the scene's lights.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "datasets/scene.h"

namespace hapcine::synth {

// One rotated ellipsoid. Texture coordinates: u = longitude (seam at the
// local -Z side, away from the object's front) times the mean horizontal
// radius, v = colatitude from the local +Y pole times the Y radius, metres.
struct MoverEllipsoid {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d world_from_local = Eigen::Matrix3d::Identity();
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();
  int texture = 0;  // index into MoverFrame::textures
};

// Parts [begin, end) of one object, inside a bounding sphere (a ray that
// misses the sphere skips them).
struct MoverGroup {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
  int begin = 0, end = 0;
};

// All movers at one instant.
struct MoverFrame {
  std::vector<MoverEllipsoid> parts;
  std::vector<MoverGroup> groups;  // every part belongs to exactly one group
  std::shared_ptr<const std::vector<std::shared_ptr<const Texture>>> textures;

  bool empty() const { return parts.empty(); }
  // Nearest mover hit with kEps < t < hit->t (hit->t is the static scene's
  // depth, or +inf); fills *hit (surface_id = kMoverSurfaceBase + part,
  // texture = -1) and *albedo. False if no part is nearer.
  bool Trace(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double footprint_per_t, Hit* hit,
             Rgb* albedo) const;
};

// Surface ids of movers start here (distinct from the static scene's, so the
// renderer antialiases their outlines).
constexpr int kMoverSurfaceBase = 1 << 24;

// Which movers a clip has.
enum class MoverKind {
  kNone,
  kHead,         // a head and shoulders close to the camera: turns, nods, blinks, talks
  kCrossing,     // three people-sized walkers crossing 2-4 m in front of the camera
  kCrowd,        // fourteen walkers, 3-9 m away, in varied directions
  kFarWalkers,   // two walkers crossing far in the back (the test-split variants)
};

// Where the head of kHead stands (the camera presets look at it).
Eigen::Vector3d MoverHeadCenter();

// The movers of `kind` at time t_s of a clip of `duration_s` (all motion is
// smooth; walkers enter and leave the hall over the clip). Deterministic in
// `seed`. Textures are painted once per process and seed.
MoverFrame MoversAt(MoverKind kind, double t_s, double duration_s, uint32_t seed);

// Lambertian shading of a mover hit with the scene's lights and ambient term
// (the same light model as Scene::Shade, without the room's corner darkening).
Rgb ShadeMover(const Scene& scene, const Hit& hit, const Rgb& albedo);

}  // namespace hapcine::synth
