#include "datasets/render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/rotation.h"
#include "datasets/scene_texture.h"

namespace hapcine::synth {
namespace {

// A group of the given primitives; its bounds come from UpdateGroupBounds().
ObjectGroup GroupOf(std::vector<int> boxes, std::vector<int> cylinders, std::vector<int> spheres) {
  ObjectGroup g;
  g.boxes = std::move(boxes);
  g.cylinders = std::move(cylinders);
  g.spheres = std::move(spheres);
  return g;
}

using Eigen::Vector2d;
using Eigen::Vector3d;

// A dark room with nothing lit but the albedo (ambient 1, no lights, no
// corner darkening near the middle), so pixel values are exact coverages.
std::shared_ptr<Scene> DarkRoom() {
  auto s = std::make_shared<Scene>();
  s->room.lo = Vector3d(-50, -50, -50);
  s->room.hi = Vector3d(50, 50, 50);
  s->textures.push_back(std::make_shared<Texture>(
      [](double, double) { return Rgb(0.1f, 0.1f, 0.1f); }, 100, 100, 1.0, false, 1));
  s->textures.push_back(std::make_shared<Texture>(
      [](double, double) { return Rgb(0.9f, 0.9f, 0.9f); }, 1, 1, 0.1, true, 1));
  for (int& t : s->room.texture) t = 0;
  s->ambient = 1;
  return s;
}

// Coverage-weighted centroid of the bright object, continuous pixel coords.
Vector2d BrightCentroid(const cv::Mat& img) {
  double sw = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      // Texture bytes: 0.1 -> 26, 0.9 -> 230 (rounded), rendered as bytes.
      const double w = (img.at<cv::Vec3f>(y, x)[1] - 26.0) / (230.0 - 26.0);
      sw += w;
      sx += w * (x + 0.5);
      sy += w * (y + 0.5);
    }
  }
  return Vector2d(sx / sw, sy / sw);
}

TEST(CameraRayDirection, PixelCentreConvention) {
  // Pixel (i, j) has its centre at (i + 0.5, j + 0.5); the principal point
  // is (W/2, H/2); image y goes down while camera +Y goes up.
  const double f = 100;
  const Vector3d d = CameraRayDirection(1.5, 0.5, 4, 2, f);
  EXPECT_DOUBLE_EQ(d.x(), -0.5 / f);
  EXPECT_DOUBLE_EQ(d.y(), 0.5 / f);
  EXPECT_DOUBLE_EQ(d.z(), -1);
  const Vector3d c = CameraRayDirection(2, 1, 4, 2, f);
  EXPECT_EQ(c, Vector3d(0, 0, -1));
}

TEST(CameraView, FocalFromHorizontalFov) {
  CameraView v;
  v.width = 1280;
  v.fov_deg = 90;
  EXPECT_NEAR(v.focal_px(), 640, 1e-9);
}

TEST(ProjectToImage, InvertsRayDirection) {
  CameraView v;
  v.width = 640;
  v.height = 360;
  v.fov_deg = 47;
  v.center = Vector3d(1, 2, 3);
  v.world_from_cam = QuaternionFromPanTiltRoll({30, -12, 8});
  for (double x : {0.0, 17.25, 320.0, 639.9}) {
    for (double y : {0.0, 100.5, 359.0}) {
      const Vector3d d =
          v.world_from_cam * CameraRayDirection(x, y, v.width, v.height, v.focal_px());
      Vector2d xy;
      ASSERT_TRUE(ProjectToImage(v, v.center + 7.3 * d, &xy));
      EXPECT_NEAR(xy.x(), x, 1e-9);
      EXPECT_NEAR(xy.y(), y, 1e-9);
    }
  }
  // Behind the camera: no projection.
  Vector2d xy;
  EXPECT_FALSE(ProjectToImage(v, v.center - v.world_from_cam * Vector3d(0, 0, -1), &xy));
}

TEST(RenderView, FrontoParallelSquareLandsAtProjectedPixel) {
  // A square facing the camera projects to a square centred exactly on the
  // projection of its centre; with supersampling the rendered coverage
  // centroid must agree to a small fraction of a pixel.
  auto scene = DarkRoom();
  BoxPrim b;
  b.center = Vector3d(0.37, -0.213, -5);
  b.half = Vector3d(0.3, 0.25, 0.01);
  for (int& t : b.texture) t = 1;
  scene->boxes.push_back(b);
  scene->groups.push_back(GroupOf({0}, {}, {}));
  scene->UpdateGroupBounds();
  CameraView v;
  v.width = 160;
  v.height = 120;
  v.fov_deg = 60;
  RenderOptions o;
  o.supersample = 8;
  o.adaptive = true;
  const cv::Mat img = RenderView(*scene, v, o);
  Vector2d expected;
  ASSERT_TRUE(ProjectToImage(v, b.center + Vector3d(0, 0, b.half.z()), &expected));
  const Vector2d got = BrightCentroid(img);
  // Coverage of axis-aligned edges is quantised to 1/8 px by the 8x8 grid.
  EXPECT_NEAR(got.x(), expected.x(), 0.04);
  EXPECT_NEAR(got.y(), expected.y(), 0.04);
  // +X right and +Y up: the square (right of and below the axis) is in the
  // lower-right quadrant.
  EXPECT_GT(got.x(), 80);
  EXPECT_GT(got.y(), 60);
}

TEST(RenderView, RotatedCameraSeesSphereOnItsAxisAtImageCentre) {
  auto scene = DarkRoom();
  CameraView v;
  v.width = 96;
  v.height = 64;
  v.fov_deg = 40;
  v.center = Vector3d(0.5, 1, 2);
  // (Room corners, whose shading darkens, stay out of view.)
  v.world_from_cam = QuaternionFromPanTiltRoll({15, -10, 30});
  // On the optical axis: a circle centred on the principal point.
  scene->spheres.push_back({v.center + v.world_from_cam * Vector3d(0, 0, -6), 0.4, 1});
  scene->groups.push_back(GroupOf({}, {}, {0}));
  scene->UpdateGroupBounds();
  RenderOptions o;
  o.supersample = 4;
  const Vector2d got = BrightCentroid(RenderView(*scene, v, o));
  EXPECT_NEAR(got.x(), 48, 0.02);
  EXPECT_NEAR(got.y(), 32, 0.02);

  // Up and to the right in the camera frame: upper-right of the image.
  scene->spheres[0].center = v.center + v.world_from_cam * Vector3d(1.0, 0.6, -6);
  scene->UpdateGroupBounds();
  const Vector2d moved = BrightCentroid(RenderView(*scene, v, o));
  EXPECT_GT(moved.x(), 60);
  EXPECT_LT(moved.y(), 25);
}

TEST(RenderView, DeterministicAcrossThreadCounts) {
  auto scene = DarkRoom();
  scene->spheres.push_back({Vector3d(0.2, 0.1, -4), 0.5, 1});
  scene->groups.push_back(GroupOf({}, {}, {0}));
  scene->UpdateGroupBounds();
  CameraView v;
  v.width = 64;
  v.height = 48;
  RenderOptions one, many;
  one.threads = 1;
  many.threads = 3;
  const cv::Mat a = RenderView(*scene, v, one), b = RenderView(*scene, v, many);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
}

TEST(LensDistortion, MapsAKnownPointWhereTheFormulaSays) {
  // x_d = x_n (1 + k1 r^2): (0.3, 0.4) has r^2 = 0.25, so k1 = -0.1 scales it by 0.975.
  const Vector2d d = DistortNormalised(Vector2d(0.3, 0.4), -0.1);
  EXPECT_NEAR(d.x(), 0.2925, 1e-15);
  EXPECT_NEAR(d.y(), 0.39, 1e-15);
  for (double k1 : {-0.2, -0.04, 0.0, 0.15}) {
    for (const Vector2d& u : {Vector2d(0.0, 0.0), Vector2d(0.01, -0.02), Vector2d(-0.6, 0.35)}) {
      const Vector2d back = UndistortNormalised(DistortNormalised(u, k1), k1);
      EXPECT_NEAR((back - u).norm(), 0, 1e-12) << k1;
    }
  }
  // Barrel distortion folds over beyond r = 1/sqrt(-3 k1).
  EXPECT_NEAR(MaxDistortedRadius(-0.12), (1 / std::sqrt(0.36)) * (1 - 0.12 / 0.36), 1e-12);
  EXPECT_TRUE(std::isinf(MaxDistortedRadius(0.1)));

  // ProjectToImage applies it in pixels around the image centre with focal_px.
  CameraView v;
  v.width = 640;
  v.height = 360;
  v.fov_deg = 60;
  v.k1 = -0.1;
  const double f = v.focal_px();
  Vector2d xy;
  // Camera frame: +y up, so image y_n = 0.4 (down) is camera y = -0.4.
  ASSERT_TRUE(ProjectToImage(v, Vector3d(0.3, -0.4, -1) * 2.5, &xy));
  EXPECT_NEAR(xy.x(), 320 + f * 0.2925, 1e-9);
  EXPECT_NEAR(xy.y(), 180 + f * 0.39, 1e-9);
}

TEST(RenderView, DistortedSphereLandsAtTheDistortedProjection) {
  auto scene = DarkRoom();
  CameraView v;
  v.width = 160;
  v.height = 120;
  v.fov_deg = 60;
  v.k1 = -0.15;
  scene->spheres.push_back({Vector3d(0.5, -0.3, -1) * 6, 0.12, 1});
  scene->groups.push_back(GroupOf({}, {}, {0}));
  scene->UpdateGroupBounds();
  RenderOptions o;
  o.supersample = 4;
  const Vector2d got = BrightCentroid(RenderView(*scene, v, o));
  Vector2d expected, pinhole;
  ASSERT_TRUE(ProjectToImage(v, scene->spheres[0].center, &expected));
  CameraView ideal = v;
  ideal.k1 = 0;
  ASSERT_TRUE(ProjectToImage(ideal, scene->spheres[0].center, &pinhole));
  EXPECT_GT((expected - pinhole).norm(), 3);  // the distortion is visible ...
  EXPECT_NEAR(got.x(), expected.x(), 0.2);    // ... and the render follows it
  EXPECT_NEAR(got.y(), expected.y(), 0.2);
  // A k1 that folds the image before its corner is refused.
  v.k1 = -0.2;
  v.fov_deg = 120;
  EXPECT_THROW(RenderView(*scene, v, o), UsageError);
}

TEST(RenderView, MoversOccludeTheSceneOnlyWhereTheyAreNearer) {
  auto scene = DarkRoom();
  scene->spheres.push_back({Vector3d(0.5, 0, -5), 0.4, 1});  // bright, right of the axis
  scene->groups.push_back(GroupOf({}, {}, {0}));
  scene->UpdateGroupBounds();
  CameraView v;
  v.width = 96;
  v.height = 64;
  v.fov_deg = 50;
  RenderOptions o;
  const cv::Mat before = RenderView(*scene, v, o);
  // A mover made of one ellipsoid, left of the axis, nearer than the room's wall.
  auto movers = std::make_shared<MoverFrame>(MoversAt(MoverKind::kHead, 0, 7, 1));
  movers->parts.resize(1);
  movers->parts[0].center = Vector3d(-0.8, 0, -4);
  movers->parts[0].radii = Vector3d(0.5, 0.7, 0.3);
  movers->groups = {{movers->parts[0].center, 0.7, 0, 1}};
  v.movers = movers;
  const cv::Mat after = RenderView(*scene, v, o);
  Vector2d mover_px, sphere_px;
  ASSERT_TRUE(ProjectToImage(v, movers->parts[0].center, &mover_px));
  ASSERT_TRUE(ProjectToImage(v, scene->spheres[0].center, &sphere_px));
  const auto at = [](const cv::Mat& m, const Vector2d& p) {
    return m.at<cv::Vec3f>(static_cast<int>(p.y()), static_cast<int>(p.x()));
  };
  EXPECT_GT(cv::norm(at(after, mover_px) - at(before, mover_px)), 10);  // the mover is drawn
  EXPECT_EQ(at(after, sphere_px), at(before, sphere_px));               // the sphere is untouched
  // Behind the sphere, a mover is hidden.
  movers->parts[0].center = Vector3d(0.5, 0, -8);
  movers->groups[0].center = movers->parts[0].center;
  EXPECT_EQ(at(RenderView(*scene, v, o), sphere_px), at(before, sphere_px));
}

TEST(RenderOptions, RejectsBadSupersample) {
  RenderOptions o;
  o.supersample = 0;
  EXPECT_THROW(o.Check(), UsageError);
  o.supersample = 9;
  EXPECT_THROW(o.Check(), UsageError);
}

TEST(Texture, MipmapsAverageAndWrap) {
  // A 2-texel-period checkerboard averages to grey in the coarser levels,
  // and wrapped lookups repeat.
  Texture t(
      [](double u, double v) {
        const int i = static_cast<int>(std::floor(u * 10)),
                  j = static_cast<int>(std::floor(v * 10));
        return ((i + j) & 1) ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
      },
      1.6, 1.6, 0.1, true, 1);
  ASSERT_EQ(t.width_px(), 16);
  EXPECT_GE(t.levels(), 5);
  EXPECT_NEAR(t.Texel(1, 3, 5)[0], 0.5, 0.01);
  EXPECT_NEAR(t.SampleTrilinear(0.05, 0.05, 1.6)[0], 0.5, 0.01);  // a whole-texture footprint
  const Rgb a = t.SampleTrilinear(0.33, 0.71, 0.01),
            b = t.SampleTrilinear(0.33 + 1.6, 0.71 - 3.2, 0.01);
  EXPECT_NEAR((a - b).norm(), 0, 1e-6);
}

}  // namespace
}  // namespace hapcine::synth
