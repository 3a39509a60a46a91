#pragma once
// The synthetic world: a room (the inside of an axis-aligned box), with
// boxes, vertical cylinders and spheres standing in it, each surface carrying a
// band-limited procedural texture (scene_texture.h), lit by a few point lights
// with view-independent (Lambertian) shading so that a scene point has the
// same colour from every viewpoint (what feature trackers assume).
//
// Geometry is analytic and deliberately simple so a CPU ray caster can render
// 1280x720 frames in a fraction of a second: a ray first finds where it leaves
// the room, then tests only the object groups whose bounding box it crosses.
//
// World frame (camera-path.md): +X right, +Y up, +Z towards the viewer;
// metres; the floor is y = 0.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "datasets/scene_texture.h"

namespace hapcine::synth {

// Result of a ray cast. The ray is o + t d with d NOT normalised: the renderer
// passes d = R_wc * (x, y, -1), so t is the depth along the camera's axis.
struct Hit {
  double t = 0;
  int surface_id = -1;          // distinct per primitive face; -1 = no hit
  int texture = -1;             // index into Scene::textures
  Eigen::Vector3d p, n;         // hit point, unit normal facing the ray
  Eigen::Vector3d tan_u, tan_v; // unit surface directions of texture u and v
  double u_m = 0, v_m = 0;      // texture coordinates, metres
  int room_face = -1;           // 0..5 for room faces (see Room), else -1
};

// The room's faces, in this order: 0 left wall (x = lo.x), 1 right wall
// (x = hi.x), 2 floor (y = lo.y), 3 ceiling (y = hi.y), 4 back wall
// (z = lo.z), 5 front wall (z = hi.z, behind the default camera).
struct Room {
  Eigen::Vector3d lo, hi;
  int texture[6] = {-1, -1, -1, -1, -1, -1};
};

// Box rotated by yaw about +Y. Faces: 0 -X, 1 +X, 2 -Y, 3 +Y, 4 -Z, 5 +Z (local).
struct BoxPrim {
  Eigen::Vector3d center, half;
  double yaw_rad = 0;
  int texture[6] = {-1, -1, -1, -1, -1, -1};
  double uv_offset_m = 0;  // shifts texture lookups so shared textures differ
};

// Vertical cylinder (axis +Y) with flat caps. Side texture wraps around:
// u = arc length from the -Z side, v = height above y0.
struct CylinderPrim {
  double x = 0, z = 0, y0 = 0, y1 = 1, radius = 0.1;
  int texture_side = -1, texture_cap = -1;
  double u_offset_m = 0;
};

// Sphere; u = arc length along the equator (the seam faces -Z, away from the
// default camera), v = arc length from the south pole.
struct SpherePrim {
  Eigen::Vector3d center;
  double radius = 0.1;
  int texture = -1;
};

struct PointLight {
  Eigen::Vector3d pos;
  float intensity = 1;
  double falloff_m = 4;  // distance at which the light has dropped to half
};

// A soft dark ellipse on the floor under an object (fake contact shadow).
struct FloorShadow {
  double x = 0, z = 0, radius_x = 0.5, radius_z = 0.5;
  float strength = 0.4f;
};

struct ObjectGroup {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  // bounding box of all members
  std::vector<int> boxes, cylinders, spheres;
};

class Scene {
 public:
  Room room;
  std::vector<BoxPrim> boxes;
  std::vector<CylinderPrim> cylinders;
  std::vector<SpherePrim> spheres;
  std::vector<ObjectGroup> groups;  // every primitive must belong to one group
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<PointLight> lights;
  std::vector<FloorShadow> floor_shadows;
  float ambient = 0.35f;

  // Nearest hit with t > 0. False (and hit->surface_id = -1) if the ray
  // misses everything, which only happens from outside the room.
  bool Trace(const Eigen::Vector3d& o, const Eigen::Vector3d& d, Hit* hit) const;

  // Colour seen along d at `hit`. `footprint_m` is the width of the pixel (or
  // sub-sample) at the hit's depth, measured across the view axis
  // (t / focal_px for a full pixel); the texture filter widens it by the
  // surface's slant.
  Rgb Shade(const Hit& hit, const Eigen::Vector3d& d, double footprint_m) const;

  // Recomputes every group's bounding box from its members.
  void UpdateGroupBounds();
};

}  // namespace hapcine::synth
