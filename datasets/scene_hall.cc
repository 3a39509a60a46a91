#include "datasets/scene_hall.h"

#include <cmath>

#include "datasets/scene_materials.h"

namespace hapcine::synth {
namespace {

using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

class HallBuilder {
 public:
  HallBuilder(uint32_t seed, SceneStyle style, int threads)
      : seed_(seed),
        flat_(style != SceneStyle::kTextured),
        albedo_(style == SceneStyle::kDarkLowTexture ? 0.2f : 1.0f),
        threads_(threads) {
    scene_ = std::make_shared<Scene>();
  }

  std::shared_ptr<const Scene> Build() {
    BuildRoom();
    BuildPillars();
    BuildFurniture();
    BuildCharacter(Vector3d(-0.42, 0, -4.0), 1.0, 0);
    BuildCharacter(Vector3d(0.48, 0, -4.25), 1.05, 1);
    Scene& s = *scene_;
    s.lights = {{Vector3d(-3, 4.6, -3), 0.42f, 5.0},
                {Vector3d(3, 4.6, -3), 0.42f, 5.0},
                {Vector3d(0, 4.6, -8.5), 0.42f, 5.0},
                {Vector3d(0, 4.6, 2.5), 0.35f, 5.0}};
    s.ambient = 0.42f;
    s.UpdateGroupBounds();
    return scene_;
  }

 private:
  uint32_t Seed(uint32_t k) const { return seed_ * 7919U + k * 104729U; }

  // Adds a texture; in the low-texture style every pattern becomes a flat
  // colour with faint large-scale shading.
  int AddTexture(const Painter& rich, Rgb flat_colour, double w_m, double h_m, double texel_m,
                 bool wrap, uint32_t k) {
    Painter p = flat_ ? FlatPainter(Seed(k), flat_colour * albedo_, 0.03f) : rich;
    if (flat_) texel_m = std::max(texel_m, 0.02);
    scene_->textures.push_back(std::make_shared<Texture>(p, w_m, h_m, texel_m, wrap, threads_));
    return static_cast<int>(scene_->textures.size()) - 1;
  }

  int AddBox(ObjectGroup* g, Vector3d center, Vector3d half, double yaw_deg, int tex,
             double uv_offset = 0, int top_tex = -1) {
    BoxPrim b;
    b.center = center;
    b.half = half;
    b.yaw_rad = yaw_deg * kPi / 180;
    for (int& t : b.texture) t = tex;
    if (top_tex >= 0) b.texture[3] = top_tex;
    b.uv_offset_m = uv_offset;
    scene_->boxes.push_back(b);
    g->boxes.push_back(static_cast<int>(scene_->boxes.size()) - 1);
    return g->boxes.back();
  }

  void AddCylinder(ObjectGroup* g, double x, double z, double y0, double y1, double r, int side,
                   int cap, double u_offset = 0) {
    CylinderPrim c;
    c.x = x;
    c.z = z;
    c.y0 = y0;
    c.y1 = y1;
    c.radius = r;
    c.texture_side = side;
    c.texture_cap = cap;
    c.u_offset_m = u_offset;
    scene_->cylinders.push_back(c);
    g->cylinders.push_back(static_cast<int>(scene_->cylinders.size()) - 1);
  }

  void AddSphere(ObjectGroup* g, Vector3d c, double r, int tex) {
    scene_->spheres.push_back({c, r, tex});
    g->spheres.push_back(static_cast<int>(scene_->spheres.size()) - 1);
  }

  void BuildRoom() {
    Room& room = scene_->room;
    room.lo = Vector3d(-7, 0, -12);
    room.hi = Vector3d(7, 5, 6);
    const double w = 14, h = 5, d = 18;
    // Side walls: stone blocks with posters.
    for (int side = 0; side < 2; ++side) {
      Painter brick = BrickPainter(Seed(10 + side), Rgb(0.62f, 0.36f, 0.26f),
                                   Rgb(0.72f, 0.7f, 0.64f), 0.42, 0.21, 0.018);
      auto posters = RandomPosters(Seed(20 + side), 7, 0.6, d - 0.6, 1.0, 4.2, 0.6, 1.7);
      room.texture[side] = AddTexture(WithPosters(brick, posters), Rgb(0.7f, 0.62f, 0.55f), d,
                                      h, 0.008, false, 30 + side);
    }
    // Floor: marble tiles. Ceiling: panels with lamps.
    room.texture[2] = AddTexture(
        TilePainter(Seed(40), 0.6, Rgb(0.78f, 0.74f, 0.68f), Rgb(0.3f, 0.28f, 0.3f),
                    Rgb(0.5f, 0.48f, 0.45f)),
        Rgb(0.55f, 0.53f, 0.5f), w, d, 0.01, false, 41);
    room.texture[3] = AddTexture(
        CeilingPainter(Seed(42), 1.2, Rgb(0.85f, 0.83f, 0.78f), Rgb(0.4f, 0.32f, 0.25f)),
        Rgb(0.8f, 0.8f, 0.78f), w, d, 0.016, false, 43);
    // Back wall: wainscot below 1.1 m, plaster above, paintings.
    {
      Painter wood = WoodPainter(Seed(50), Rgb(0.6f, 0.4f, 0.22f), Rgb(0.3f, 0.17f, 0.08f), 0.18);
      Painter plaster = PlasterPainter(Seed(51), Rgb(0.78f, 0.72f, 0.6f), 0.18f);
      Painter back = [wood, plaster](double u, double v) -> Rgb {
        if (v < 1.1) return wood(u, v);
        if (v < 1.16) return Rgb(0.25f, 0.15f, 0.08f);  // rail
        return plaster(u, v);
      };
      auto posters = RandomPosters(Seed(52), 5, 0.5, w - 0.5, 1.4, 4.4, 0.8, 2.0);
      room.texture[4] = AddTexture(WithPosters(back, posters), Rgb(0.75f, 0.7f, 0.6f), w, h,
                                   0.008, false, 53);
    }
    {
      Painter brick = BrickPainter(Seed(60), Rgb(0.5f, 0.52f, 0.55f), Rgb(0.8f, 0.78f, 0.72f),
                                   0.5, 0.25, 0.02);
      auto posters = RandomPosters(Seed(61), 4, 0.5, w - 0.5, 1.0, 4.2, 0.7, 1.6);
      room.texture[5] = AddTexture(WithPosters(brick, posters), Rgb(0.6f, 0.6f, 0.62f), w, h,
                                   0.008, false, 62);
    }
  }

  void BuildPillars() {
    const double r = 0.3, circ = 2 * kPi * r;
    const int side = AddTexture(FlutedPainter(Seed(70), Rgb(0.82f, 0.8f, 0.74f), 0.1, circ),
                                Rgb(0.8f, 0.78f, 0.74f), circ, 5.0, 0.005, true, 71);
    const int stone = AddTexture(NoisyPainter(Seed(72), Rgb(0.55f, 0.52f, 0.48f), 0.35f, 6, 0),
                                 Rgb(0.55f, 0.52f, 0.5f), 2.0, 2.0, 0.004, true, 73);
    int k = 0;
    for (double x : {-4.0, 4.0}) {
      for (double z : {-1.0, -5.0, -9.0}) {
        ObjectGroup g;
        AddCylinder(&g, x, z, 0.3, 5.0, r, side, side, 0.37 * k);
        AddBox(&g, Vector3d(x, 0.15, z), Vector3d(0.42, 0.15, 0.42), 0, stone, 0.31 * k);
        scene_->groups.push_back(g);
        scene_->floor_shadows.push_back({x, z, 0.75, 0.75, 0.45f});
        ++k;
      }
    }
  }

  void BuildFurniture() {
    const int crate = AddTexture(WoodPainter(Seed(80), Rgb(0.72f, 0.55f, 0.32f),
                                             Rgb(0.42f, 0.28f, 0.14f), 0.12),
                                 Rgb(0.65f, 0.5f, 0.32f), 3.0, 3.0, 0.004, true, 81);
    const int dark_wood = AddTexture(WoodPainter(Seed(82), Rgb(0.45f, 0.26f, 0.14f),
                                                 Rgb(0.2f, 0.1f, 0.05f), 0.2),
                                     Rgb(0.35f, 0.22f, 0.12f), 3.0, 3.0, 0.004, true, 83);
    const int metal = AddTexture(NoisyPainter(Seed(84), Rgb(0.25f, 0.26f, 0.28f), 0.3f, 20, 0),
                                 Rgb(0.25f, 0.26f, 0.28f), 1.0, 2.0, 0.004, true, 85);
    const int shade_tex = AddTexture(
        StripesPainter(Seed(86), {Rgb(0.9f, 0.85f, 0.6f), Rgb(0.7f, 0.2f, 0.15f)}, 0.05,
                       2 * kPi * 0.2),
        Rgb(0.9f, 0.85f, 0.65f), 2 * kPi * 0.2, 0.4, 0.003, true, 87);
    const int globe = AddTexture(ChecksPainter(Seed(88), Rgb(0.15f, 0.35f, 0.7f),
                                               Rgb(0.3f, 0.6f, 0.3f), 0.04, 2 * kPi * 0.15),
                                 Rgb(0.3f, 0.45f, 0.6f), 2 * kPi * 0.15, kPi * 0.15, 0.002, true,
                                 89);
    const int books = AddTexture(StripesPainter(Seed(90),
                                                {Rgb(0.7f, 0.1f, 0.1f), Rgb(0.1f, 0.2f, 0.6f),
                                                 Rgb(0.9f, 0.8f, 0.2f), Rgb(0.1f, 0.5f, 0.2f)},
                                                0.03, 0),
                                 Rgb(0.5f, 0.3f, 0.3f), 1.0, 1.0, 0.002, true, 91);
    {  // Crates, left foreground.
      ObjectGroup g;
      AddBox(&g, Vector3d(-1.9, 0.3, -2.3), Vector3d(0.3, 0.3, 0.3), 12, crate, 0.0);
      AddBox(&g, Vector3d(-1.85, 0.85, -2.32), Vector3d(0.25, 0.25, 0.25), -18, crate, 0.9);
      AddBox(&g, Vector3d(-1.25, 0.2, -2.0), Vector3d(0.2, 0.2, 0.2), 35, crate, 1.7);
      scene_->groups.push_back(g);
      scene_->floor_shadows.push_back({-1.75, -2.2, 0.75, 0.6, 0.5f});
    }
    {  // Standing lamp, right foreground.
      ObjectGroup g;
      AddCylinder(&g, 1.7, -2.2, 0.0, 0.04, 0.18, metal, metal);
      AddCylinder(&g, 1.7, -2.2, 0.04, 1.6, 0.025, metal, metal);
      AddCylinder(&g, 1.7, -2.2, 1.55, 1.9, 0.2, shade_tex, metal);
      scene_->groups.push_back(g);
      scene_->floor_shadows.push_back({1.7, -2.2, 0.35, 0.35, 0.4f});
    }
    {  // Table with a globe and books, right middle ground.
      ObjectGroup g;
      const Vector3d c(2.3, 0, -6.6);
      AddBox(&g, c + Vector3d(0, 0.76, 0), Vector3d(0.8, 0.03, 0.45), 0, dark_wood);
      for (double sx : {-0.72, 0.72}) {
        for (double sz : {-0.38, 0.38}) {
          AddBox(&g, c + Vector3d(sx, 0.365, sz), Vector3d(0.03, 0.365, 0.03), 0, dark_wood);
        }
      }
      AddSphere(&g, c + Vector3d(-0.35, 0.94, 0.05), 0.15, globe);
      AddBox(&g, c + Vector3d(0.3, 0.86, 0.0), Vector3d(0.2, 0.07, 0.14), 20, books);
      AddBox(&g, c + Vector3d(0.35, 0.98, -0.02), Vector3d(0.13, 0.05, 0.1), -10, books, 0.5);
      scene_->groups.push_back(g);
      scene_->floor_shadows.push_back({c.x(), c.z(), 1.0, 0.65, 0.45f});
    }
    {  // Bench, left middle ground.
      ObjectGroup g;
      const Vector3d c(-2.9, 0, -7.2);
      AddBox(&g, c + Vector3d(0, 0.45, 0), Vector3d(0.95, 0.04, 0.24), 8, crate, 2.3);
      AddBox(&g, c + Vector3d(-0.75, 0.205, 0.1), Vector3d(0.04, 0.205, 0.2), 8, metal);
      AddBox(&g, c + Vector3d(0.75, 0.205, -0.12), Vector3d(0.04, 0.205, 0.2), 8, metal);
      scene_->groups.push_back(g);
      scene_->floor_shadows.push_back({c.x(), c.z(), 1.1, 0.45, 0.4f});
    }
    {  // Door in the back wall, and a tall cabinet on the right wall.
      ObjectGroup g;
      AddBox(&g, Vector3d(-3.2, 1.1, -11.97), Vector3d(0.55, 1.1, 0.03), 0, dark_wood, 0.4);
      AddBox(&g, Vector3d(-3.2, 2.25, -11.94), Vector3d(0.7, 0.06, 0.06), 0, crate, 1.1);
      AddBox(&g, Vector3d(-3.86, 1.1, -11.94), Vector3d(0.06, 1.1, 0.06), 0, crate, 1.3);
      AddBox(&g, Vector3d(-2.54, 1.1, -11.94), Vector3d(0.06, 1.1, 0.06), 0, crate, 1.5);
      scene_->groups.push_back(g);
    }
    {
      ObjectGroup g;
      AddBox(&g, Vector3d(6.62, 1.0, -7.5), Vector3d(0.35, 1.0, 0.7), 0, dark_wood, 0.8);
      AddBox(&g, Vector3d(6.22, 1.2, -7.5), Vector3d(0.05, 0.5, 0.3), 0, books, 0.2);
      scene_->groups.push_back(g);
    }
  }

  // A simple standing figure facing +Z: legs, shoes, torso, arms, hands,
  // neck, head and hair. `look` selects clothes.
  void BuildCharacter(Vector3d base, double s, int look) {
    const double leg_r = 0.075 * s, arm_r = 0.055 * s, head_r = 0.115 * s, hand_r = 0.055 * s;
    const uint32_t k = 100 + 20 * look;
    const Rgb skin = look == 0 ? Rgb(0.85f, 0.64f, 0.5f) : Rgb(0.55f, 0.38f, 0.28f);
    const Rgb trousers = look == 0 ? Rgb(0.2f, 0.27f, 0.45f) : Rgb(0.3f, 0.28f, 0.22f);
    Painter shirt = look == 0
        ? StripesPainter(Seed(k), {Rgb(0.85f, 0.2f, 0.15f), Rgb(0.95f, 0.92f, 0.85f),
                                   Rgb(0.15f, 0.2f, 0.4f)}, 0.04, 0)
        : ChecksPainter(Seed(k), Rgb(0.15f, 0.45f, 0.25f), Rgb(0.85f, 0.8f, 0.3f), 0.05, 0);
    Painter sleeve = look == 0
        ? StripesPainter(Seed(k), {Rgb(0.85f, 0.2f, 0.15f), Rgb(0.95f, 0.92f, 0.85f),
                                   Rgb(0.15f, 0.2f, 0.4f)}, 0.04, 2 * kPi * arm_r)
        : ChecksPainter(Seed(k), Rgb(0.15f, 0.45f, 0.25f), Rgb(0.85f, 0.8f, 0.3f), 0.05,
                        2 * kPi * arm_r);
    const Rgb shirt_flat = look == 0 ? Rgb(0.7f, 0.3f, 0.25f) : Rgb(0.3f, 0.5f, 0.3f);
    const int t_shirt = AddTexture(shirt, shirt_flat, 1.0, 1.0, 0.002, true, k + 1);
    const int t_sleeve = AddTexture(sleeve, shirt_flat, 2 * kPi * arm_r, 0.8, 0.002, true, k + 2);
    const int t_leg = AddTexture(NoisyPainter(Seed(k + 3), trousers, 0.35f, 30, 2 * kPi * leg_r),
                                 trousers, 2 * kPi * leg_r, 1.0, 0.002, true, k + 3);
    const int t_shoe = AddTexture(NoisyPainter(Seed(k + 4), Rgb(0.12f, 0.1f, 0.09f), 0.4f, 25, 0),
                                  Rgb(0.12f, 0.1f, 0.09f), 1.0, 1.0, 0.003, true, k + 4);
    const int t_head = AddTexture(NoisyPainter(Seed(k + 5), skin, 0.18f, 25, 2 * kPi * head_r),
                                  skin, 2 * kPi * head_r, kPi * head_r, 0.0015, true, k + 5);
    const int t_hair = AddTexture(
        NoisyPainter(Seed(k + 6), look == 0 ? Rgb(0.3f, 0.18f, 0.08f) : Rgb(0.08f, 0.07f, 0.06f),
                     0.5f, 60, 2 * kPi * (head_r * 1.04)),
        Rgb(0.2f, 0.12f, 0.08f), 2 * kPi * head_r * 1.04, kPi * head_r * 1.04, 0.0015, true,
        k + 6);
    const int t_hand = AddTexture(NoisyPainter(Seed(k + 7), skin, 0.15f, 30, 2 * kPi * hand_r),
                                  skin, 2 * kPi * hand_r, kPi * hand_r, 0.002, true, k + 7);
    const int t_skin = AddTexture(NoisyPainter(Seed(k + 8), skin, 0.15f, 30, 2 * kPi * 0.05 * s),
                                  skin, 2 * kPi * 0.05 * s, 0.3, 0.002, true, k + 8);

    ObjectGroup g;
    const double x = base.x(), z = base.z();
    for (double side : {-1.0, 1.0}) {
      AddCylinder(&g, x + side * 0.1 * s, z, 0.08 * s, 0.88 * s, leg_r, t_leg, t_leg);
      AddBox(&g, Vector3d(x + side * 0.1 * s, 0.04 * s, z + 0.04 * s),
             Vector3d(0.055 * s, 0.04 * s, 0.13 * s), side * 6, t_shoe);
      AddCylinder(&g, x + side * 0.275 * s, z, 0.82 * s, 1.43 * s, arm_r, t_sleeve, t_sleeve);
      AddSphere(&g, Vector3d(x + side * 0.275 * s, 0.79 * s, z), hand_r, t_hand);
    }
    AddBox(&g, Vector3d(x, 1.16 * s, z), Vector3d(0.21 * s, 0.3 * s, 0.12 * s), 0, t_shirt,
           0.3 * look);
    AddCylinder(&g, x, z, 1.45 * s, 1.53 * s, 0.05 * s, t_skin, t_skin);
    AddSphere(&g, Vector3d(x, 1.63 * s, z), head_r, t_head);
    AddSphere(&g, Vector3d(x, 1.655 * s, z - 0.02 * s), head_r * 1.04, t_hair);
    scene_->groups.push_back(g);
    scene_->floor_shadows.push_back({x, z, 0.45 * s, 0.35 * s, 0.5f});
  }

  uint32_t seed_;
  bool flat_;
  float albedo_;  // flat colours' factor (the dark style's)
  int threads_;
  std::shared_ptr<Scene> scene_;
};

}  // namespace

std::shared_ptr<const Scene> BuildHallScene(uint32_t seed, SceneStyle style, int threads) {
  return HallBuilder(seed, style, threads).Build();
}

Eigen::Vector3d HallSubjectCenter() { return Eigen::Vector3d(0.03, 1.15, -4.12); }

}  // namespace hapcine::synth
