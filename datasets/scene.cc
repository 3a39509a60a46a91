#include "datasets/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hapcine::synth {
namespace {

using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = 1e-9;

// Slab test of the ray against an axis-aligned box; true if [tmin, tmax]
// overlaps the box's entry/exit interval.
inline bool HitsAabb(const Vector3d& o, const Vector3d& inv_d, const Vector3d& lo,
                     const Vector3d& hi, double tmax) {
  double t0 = kEps, t1 = tmax;
  for (int i = 0; i < 3; ++i) {
    double a = (lo[i] - o[i]) * inv_d[i], b = (hi[i] - o[i]) * inv_d[i];
    if (std::isnan(a) || std::isnan(b)) {
      // d[i] == 0 with the origin on a slab face: treat as inside.
      if (o[i] < lo[i] || o[i] > hi[i]) return false;
      continue;
    }
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

void TraceBox(const BoxPrim& b, int id_base, const Vector3d& o, const Vector3d& d, Hit* hit) {
  const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
  // local = R_y(yaw)^T (world - centre)
  const Vector3d e = o - b.center;
  const Vector3d lo(c * e.x() - s * e.z(), e.y(), s * e.x() + c * e.z());
  const Vector3d ld(c * d.x() - s * d.z(), d.y(), s * d.x() + c * d.z());
  double t_near = -std::numeric_limits<double>::infinity();
  double t_far = std::numeric_limits<double>::infinity();
  int axis = -1;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(ld[i]) < 1e-15) {
      if (std::abs(lo[i]) > b.half[i]) return;
      continue;
    }
    double t1 = (-b.half[i] - lo[i]) / ld[i], t2 = (b.half[i] - lo[i]) / ld[i];
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > t_near) {
      t_near = t1;
      axis = i;
    }
    t_far = std::min(t_far, t2);
  }
  if (axis < 0 || t_near > t_far || t_near <= kEps || t_near >= hit->t) return;
  const int face = axis * 2 + (ld[axis] > 0 ? 0 : 1);
  const Vector3d lp = lo + t_near * ld;
  Vector3d ln = Vector3d::Zero();
  ln[axis] = ld[axis] > 0 ? -1 : 1;
  // Texture axes per face, in local coordinates.
  Vector3d lu, lv;
  double u, v;
  if (axis == 0) {
    lu = Vector3d::UnitZ();
    lv = Vector3d::UnitY();
    u = lp.z() + b.half.z();
    v = lp.y() + b.half.y();
  } else if (axis == 1) {
    lu = Vector3d::UnitX();
    lv = Vector3d::UnitZ();
    u = lp.x() + b.half.x();
    v = lp.z() + b.half.z();
  } else {
    lu = Vector3d::UnitX();
    lv = Vector3d::UnitY();
    u = lp.x() + b.half.x();
    v = lp.y() + b.half.y();
  }
  auto to_world = [c, s](const Vector3d& l) {
    return Vector3d(c * l.x() + s * l.z(), l.y(), -s * l.x() + c * l.z());
  };
  hit->t = t_near;
  hit->surface_id = id_base + face;
  hit->texture = b.texture[face];
  hit->p = o + t_near * d;
  hit->n = to_world(ln);
  hit->tan_u = to_world(lu);
  hit->tan_v = to_world(lv);
  hit->u_m = u + b.uv_offset_m;
  hit->v_m = v + 0.37 * b.uv_offset_m;
  hit->room_face = -1;
}

void TraceCylinder(const CylinderPrim& cy, int id_base, const Vector3d& o, const Vector3d& d,
                   Hit* hit) {
  const double ex = o.x() - cy.x, ez = o.z() - cy.z;
  const double a = d.x() * d.x() + d.z() * d.z();
  double t_side = std::numeric_limits<double>::infinity();
  if (a > 1e-18) {
    const double b = 2 * (d.x() * ex + d.z() * ez);
    const double c = ex * ex + ez * ez - cy.radius * cy.radius;
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      const double y = o.y() + t * d.y();
      if (t > kEps && y >= cy.y0 && y <= cy.y1) t_side = t;
    }
  }
  // Caps: only the one facing the ray origin can be hit first.
  double t_cap = std::numeric_limits<double>::infinity();
  double cap_y = 0;
  if (o.y() > cy.y1 && d.y() < 0) cap_y = cy.y1;
  else if (o.y() < cy.y0 && d.y() > 0) cap_y = cy.y0;
  else cap_y = std::numeric_limits<double>::quiet_NaN();
  if (!std::isnan(cap_y)) {
    const double t = (cap_y - o.y()) / d.y();
    const double px = ex + t * d.x(), pz = ez + t * d.z();
    if (t > kEps && px * px + pz * pz <= cy.radius * cy.radius) t_cap = t;
  }
  if (t_side < t_cap && t_side < hit->t) {
    const Vector3d p = o + t_side * d;
    const double dx = p.x() - cy.x, dz = p.z() - cy.z;
    const double phi = std::atan2(dx, dz);  // 0 towards +Z
    hit->t = t_side;
    hit->surface_id = id_base;
    hit->texture = cy.texture_side;
    hit->p = p;
    hit->n = Vector3d(dx, 0, dz) / cy.radius;
    hit->tan_u = Vector3d(std::cos(phi), 0, -std::sin(phi));
    hit->tan_v = Vector3d::UnitY();
    // u = arc length measured from the -Z side so the seam faces away from the
    // default camera (which looks towards -Z from +Z).
    hit->u_m = cy.radius * (phi + kPi) + cy.u_offset_m;
    hit->v_m = p.y() - cy.y0;
    hit->room_face = -1;
  } else if (t_cap < hit->t) {
    const Vector3d p = o + t_cap * d;
    hit->t = t_cap;
    hit->surface_id = id_base + 1;
    hit->texture = cy.texture_cap;
    hit->p = p;
    hit->n = Vector3d(0, d.y() < 0 ? 1 : -1, 0);
    hit->tan_u = Vector3d::UnitX();
    hit->tan_v = Vector3d::UnitZ();
    hit->u_m = p.x() - cy.x + cy.radius + cy.u_offset_m;
    hit->v_m = p.z() - cy.z + cy.radius;
    hit->room_face = -1;
  }
}

void TraceSphere(const SpherePrim& s, int id, const Vector3d& o, const Vector3d& d, Hit* hit) {
  const Vector3d e = o - s.center;
  const double a = d.squaredNorm(), b = 2 * d.dot(e), c = e.squaredNorm() - s.radius * s.radius;
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return;
  const double t = (-b - std::sqrt(disc)) / (2 * a);
  if (t <= kEps || t >= hit->t) return;
  const Vector3d p = o + t * d;
  const Vector3d n = (p - s.center) / s.radius;
  const double phi = std::atan2(n.x(), n.z());
  const double theta = std::asin(std::clamp(n.y(), -1.0, 1.0));
  hit->t = t;
  hit->surface_id = id;
  hit->texture = s.texture;
  hit->p = p;
  hit->n = n;
  hit->tan_u = Vector3d(std::cos(phi), 0, -std::sin(phi));
  hit->tan_v = Vector3d(-std::sin(theta) * std::sin(phi), std::cos(theta),
                        -std::sin(theta) * std::cos(phi));
  hit->u_m = s.radius * (phi + kPi);
  hit->v_m = s.radius * (theta + kPi / 2);
  hit->room_face = -1;
}

}  // namespace

void Scene::UpdateGroupBounds() {
  for (ObjectGroup& g : groups) {
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
    Vector3d hi = -lo;
    for (int i : g.boxes) {
      const BoxPrim& b = boxes[i];
      // A yawed box fits in a square of half-size |hx|+|hz| around its centre.
      const double r = std::hypot(b.half.x(), b.half.z());
      lo = lo.cwiseMin(b.center - Vector3d(r, b.half.y(), r));
      hi = hi.cwiseMax(b.center + Vector3d(r, b.half.y(), r));
    }
    for (int i : g.cylinders) {
      const CylinderPrim& c = cylinders[i];
      lo = lo.cwiseMin(Vector3d(c.x - c.radius, c.y0, c.z - c.radius));
      hi = hi.cwiseMax(Vector3d(c.x + c.radius, c.y1, c.z + c.radius));
    }
    for (int i : g.spheres) {
      const SpherePrim& s = spheres[i];
      lo = lo.cwiseMin(s.center - Vector3d::Constant(s.radius));
      hi = hi.cwiseMax(s.center + Vector3d::Constant(s.radius));
    }
    g.lo = lo - Vector3d::Constant(1e-6);
    g.hi = hi + Vector3d::Constant(1e-6);
  }
}

bool Scene::Trace(const Vector3d& o, const Vector3d& d, Hit* hit) const {
  hit->surface_id = -1;
  hit->t = std::numeric_limits<double>::infinity();
  // Where the ray leaves the room.
  int face = -1;
  double t_room = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-15) continue;
    const bool pos = d[i] > 0;
    const double t = ((pos ? room.hi[i] : room.lo[i]) - o[i]) / d[i];
    if (t < t_room) {
      t_room = t;
      face = i * 2 + (pos ? 1 : 0);
    }
  }
  if (face >= 0 && t_room > kEps) {
    const Vector3d p = o + t_room * d;
    hit->t = t_room;
    hit->surface_id = face;
    hit->texture = room.texture[face];
    hit->p = p;
    hit->room_face = face;
    const int axis = face / 2;
    hit->n = Vector3d::Zero();
    hit->n[axis] = (face % 2 == 0) ? 1 : -1;  // faces point into the room
    if (axis == 0) {  // side walls: u along z (from the back wall), v up
      hit->tan_u = Vector3d::UnitZ();
      hit->tan_v = Vector3d::UnitY();
      hit->u_m = p.z() - room.lo.z();
      hit->v_m = p.y() - room.lo.y();
    } else if (axis == 1) {  // floor / ceiling: u along x, v along z
      hit->tan_u = Vector3d::UnitX();
      hit->tan_v = Vector3d::UnitZ();
      hit->u_m = p.x() - room.lo.x();
      hit->v_m = p.z() - room.lo.z();
    } else {  // back / front walls: u along x, v up
      hit->tan_u = Vector3d::UnitX();
      hit->tan_v = Vector3d::UnitY();
      hit->u_m = p.x() - room.lo.x();
      hit->v_m = p.y() - room.lo.y();
    }
  }
  const Vector3d inv_d = d.cwiseInverse();
  constexpr int kIdsPerPrim = 8;
  const int box_base = 8;
  const int cyl_base = box_base + kIdsPerPrim * static_cast<int>(boxes.size());
  const int sph_base = cyl_base + kIdsPerPrim * static_cast<int>(cylinders.size());
  for (const ObjectGroup& g : groups) {
    if (!HitsAabb(o, inv_d, g.lo, g.hi, hit->t)) continue;
    for (int i : g.boxes) TraceBox(boxes[i], box_base + kIdsPerPrim * i, o, d, hit);
    for (int i : g.cylinders) {
      TraceCylinder(cylinders[i], cyl_base + kIdsPerPrim * i, o, d, hit);
    }
    for (int i : g.spheres) TraceSphere(spheres[i], sph_base + kIdsPerPrim * i, o, d, hit);
  }
  return hit->surface_id >= 0;
}

Rgb Scene::Shade(const Hit& hit, const Vector3d& d, double footprint_m) const {
  const Vector3d dn = d.normalized();
  const double cos_t = std::max(std::abs(dn.dot(hit.n)), 1e-3);
  // The footprint across the view axis is stretched by 1/cos along the
  // surface's slant direction (the projection of the ray onto the surface).
  double ratio = std::min(1.0 / cos_t, 32.0);
  double du = dn.dot(hit.tan_u), dv = dn.dot(hit.tan_v);
  const double dl = std::hypot(du, dv);
  if (dl > 1e-9) {
    du /= dl;
    dv /= dl;
  } else {
    du = 1;
    dv = 0;
    ratio = 1;
  }
  Rgb albedo(0.5f, 0.5f, 0.5f);
  if (hit.texture >= 0) {
    albedo = textures[hit.texture]->Sample(hit.u_m, hit.v_m, footprint_m, ratio, du, dv);
  }
  // Lambertian lighting: ambient plus point lights with a soft falloff.
  float light = ambient;
  for (const PointLight& l : lights) {
    const Vector3d to = l.pos - hit.p;
    const double dist2 = to.squaredNorm();
    const double ndl = hit.n.dot(to) / std::sqrt(dist2);
    if (ndl <= 0) continue;
    light += static_cast<float>(l.intensity * ndl / (1 + dist2 / (l.falloff_m * l.falloff_m)));
  }
  // Darker room corners (cheap ambient occlusion): distance to the nearest
  // perpendicular room face.
  if (hit.room_face >= 0) {
    const int axis = hit.room_face / 2;
    double near = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      if (i == axis) continue;
      near = std::min({near, hit.p[i] - room.lo[i], room.hi[i] - hit.p[i]});
    }
    const double k = std::max(0.0, 1 - near / 0.6);
    light *= static_cast<float>(1 - 0.35 * k * k);
    if (hit.room_face == 2) {
      for (const FloorShadow& s : floor_shadows) {
        const double x = (hit.p.x() - s.x) / s.radius_x, z = (hit.p.z() - s.z) / s.radius_z;
        const double r2 = x * x + z * z;
        if (r2 < 1) light *= 1 - s.strength * static_cast<float>((1 - r2) * (1 - r2));
      }
    }
  }
  return albedo * light;
}

}  // namespace hapcine::synth
