// Independent motion is not camera motion (motion_hypotheses.h): synthetic
// tracks of scenes with moving subjects — a head filling half the frame, a
// person crossing during a pan or a traveling, a crowd — and the cases that
// must keep their motion (a camera following a subject, a pan with
// parallax).

#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <map>
#include <random>

#include "core/rotation.h"
#include "estimate/test_scene.h"
#include "estimate/track_estimator.h"

namespace hapcine {
namespace {

using testing::Ease;
using testing::ProjectPx;
using testing::RandomPoints;
using testing::SceneCamera;

constexpr int kW = 960, kH = 540;
constexpr double kFocal = 800;
constexpr long kIdGap = 100000;  // track ids of mover points start here

// A rigid ellipsoid moving on its own: its surface carries the tracks (the
// half facing the camera is seen) and it hides what lies behind it.
struct Mover {
  Eigen::Vector3d radii;
  std::function<Eigen::Isometry3d(int)> pose;  // world_from_body at frame i
  std::vector<Eigen::Vector3d> surface;        // body coordinates
};

std::vector<Eigen::Vector3d> SurfacePoints(const Eigen::Vector3d& radii, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    pts.push_back(d.cwiseProduct(radii));
  }
  return pts;
}

// Does the segment from the camera centre to X pass through the ellipsoid?
bool Hidden(const Mover& m, const Eigen::Isometry3d& world_from_body, const Eigen::Vector3d& centre,
            const Eigen::Vector3d& X) {
  const Eigen::Isometry3d body_from_world = world_from_body.inverse();
  const Eigen::Vector3d a = (body_from_world * centre).cwiseQuotient(m.radii);
  const Eigen::Vector3d b = (body_from_world * X).cwiseQuotient(m.radii);
  const Eigen::Vector3d d = b - a;
  const double A = d.squaredNorm(), B = 2 * a.dot(d), C = a.squaredNorm() - 1;
  const double disc = B * B - 4 * A * C;
  if (disc <= 0) return false;
  const double s = (-B - std::sqrt(disc)) / (2 * A);
  return s > 1e-6 && s < 1 - 1e-6;
}

// Tracks of a background and movers: a track ends when its point is hidden
// or leaves the frame, and a point seen again is a new track.
class MoverScene {
 public:
  MoverScene(std::vector<Eigen::Vector3d> background, std::vector<Mover> movers)
      : background_(std::move(background)), movers_(std::move(movers)) {}

  FrameTracks Frame(int i, const SceneCamera& cam, std::mt19937* rng) {
    FrameTracks ft;
    ft.index = i;
    ft.time_s = i / 25.0;
    ft.quality = 1;
    ft.boundary = i == 0 ? ShotBoundary::kStart : ShotBoundary::kNone;
    std::normal_distribution<double> noise(0, 0.3);
    poses_.clear();
    for (const Mover& m : movers_) poses_.push_back(m.pose(i));
    auto add = [&](long k, const Eigen::Vector3d& X, const std::function<bool()>& visible) {
      Eigen::Vector2d px;
      if (!ProjectPx(cam, X, kW, kH, &px) || !visible()) {
        seen_[k] = false;
        return;
      }
      if (!seen_[k]) ++episode_[k];
      seen_[k] = true;
      ft.points.push_back({k + 1000000L * episode_[k], px + Eigen::Vector2d(noise(*rng), noise(*rng))});
    };
    for (size_t j = 0; j < background_.size(); ++j)
      add(static_cast<long>(j), background_[j], [&] { return !HiddenByAny(cam.center, background_[j], -1); });
    long key = kIdGap;
    for (size_t m = 0; m < movers_.size(); ++m) {
      const Eigen::Vector3d r2 = movers_[m].radii.cwiseProduct(movers_[m].radii);
      for (const Eigen::Vector3d& p : movers_[m].surface) {
        const Eigen::Vector3d X = poses_[m] * p;
        const Eigen::Vector3d normal = poses_[m].linear() * p.cwiseQuotient(r2);
        add(key++, X, [&] {
          return normal.dot(cam.center - X) > 0 && !HiddenByAny(cam.center, X, static_cast<int>(m));
        });
      }
    }
    return ft;
  }

 private:
  bool HiddenByAny(const Eigen::Vector3d& centre, const Eigen::Vector3d& X, int self) const {
    for (size_t m = 0; m < movers_.size(); ++m)
      if (static_cast<int>(m) != self && Hidden(movers_[m], poses_[m], centre, X)) return true;
    return false;
  }
  std::vector<Eigen::Isometry3d> poses_;  // the movers' at the current frame
  std::vector<Eigen::Vector3d> background_;
  std::vector<Mover> movers_;
  std::map<long, bool> seen_;
  std::map<long, int> episode_;
};

struct MoverRun {
  CameraPath path;
  double mean_rot_err_deg = 0;
  double max_abs_translation = 0;
  Eigen::Vector3d end_center = Eigen::Vector3d::Zero();
  std::map<std::string, int> models;
  int mover_share_percent = 0;  // of the first frame's tracks
};

MoverRun Simulate(int frames, const std::function<SceneCamera(int)>& camera_at, MoverScene scene,
             const TrackEstimatorOptions& opt = {}) {
  TrackCameraEstimator est(kW, kH, opt);
  std::mt19937 rng(7);
  std::vector<SceneCamera> truth;
  MoverRun run;
  for (int i = 0; i < frames; ++i) {
    truth.push_back(camera_at(i));
    const FrameTracks ft = scene.Frame(i, truth.back(), &rng);
    if (i == 0) {
      int movers = 0;
      for (const auto& p : ft.points) movers += (p.track_id % 1000000L) >= kIdGap;
      run.mover_share_percent = static_cast<int>(100 * movers / std::max<size_t>(ft.points.size(), 1));
    }
    est.AddFrame(ft);
  }
  run.path = est.Finish();
  double sum = 0;
  for (int i = 0; i < frames; ++i) {
    const CameraFrame& f = run.path.frames[i];
    // The path starts at the identity: the truth relative to its first frame.
    sum += AngleBetweenDeg(f.world_from_cam, truth[0].world_from_cam.conjugate() * truth[i].world_from_cam);
    run.max_abs_translation = std::max(run.max_abs_translation, f.center.cwiseAbs().maxCoeff());
    ++run.models[*f.model];
  }
  run.mean_rot_err_deg = sum / frames;

  run.end_center = run.path.frames.back().center;
  return run;
}

void Print(const std::string& name, const MoverRun& r) {
  std::cout << name << ": movers " << r.mover_share_percent << " % of the tracks, rotation " << r.mean_rot_err_deg
            << " deg, max |centre| " << r.max_abs_translation << ", models";
  for (const auto& [m, n] : r.models) std::cout << " " << m << "=" << n;
  std::cout << "\n";
}

// The background: a wall of points 4 m away covering the frame (and more,
// for pans), as dense as the tracker leaves them.
std::vector<Eigen::Vector3d> Wall(int n, double depth, double spread, unsigned seed) {
  return RandomPoints(n, depth, depth, spread, seed);
}

SceneCamera Still() {
  SceneCamera c;
  c.focal_px = kFocal;
  return c;
}

SceneCamera Pan(int i, int frames, double deg) {
  SceneCamera c;
  PanTiltRoll ptr;
  ptr.pan_deg = deg * Ease(i, frames);
  c.world_from_cam = QuaternionFromPanTiltRoll(ptr);
  c.focal_px = kFocal;
  return c;
}

MoverRun WithoutSeparation(int frames, const std::function<SceneCamera(int)>& camera_at, MoverScene scene) {
  TrackEstimatorOptions opt;
  opt.movers.enabled = false;
  return Simulate(frames, camera_at, std::move(scene), opt);
}

// A head (ellipsoid 9 x 12 x 10 cm) whose outline fills `area` of the frame,
// turning (+-25 deg) and nodding (+-12 deg) about the neck.
Mover Head(double area) {
  Mover head;
  head.radii = Eigen::Vector3d(0.09, 0.12, 0.10);
  // Outline area pi a b f^2 / z^2 = area * W * H.
  const double z = kFocal * std::sqrt(kPi * 0.09 * 0.12 / (area * kW * kH));
  const Eigen::Vector3d centre(0, 0, -z);
  const Eigen::Vector3d neck = centre + Eigen::Vector3d(0, -0.14, 0);
  head.pose = [=](int i) {
    const double t = i / 25.0;
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.44 * std::sin(2 * kPi * t / 2.4), Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(0.21 * std::sin(2 * kPi * t / 1.3), Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = R;
    pose.translation() = neck + R * (centre - neck);
    return pose;
  };
  head.surface = SurfacePoints(head.radii, static_cast<int>(2400 * area), 5);
  return head;
}

TEST(TrackEstimatorMovers, HeadFillingHalfTheFrameDoesNotMoveAStillCamera) {
  for (double area : {0.4, 0.55, 0.7}) {
    MoverRun run = Simulate(150, [](int) { return Still(); }, MoverScene(Wall(700, 4, 0.6, 1), {Head(area)}));
    Print("head " + std::to_string(area), run);
    EXPECT_GT(run.mover_share_percent, 30);
    EXPECT_EQ(run.models["static"], 150);
    EXPECT_LE(run.mean_rot_err_deg, 0.3);
    EXPECT_EQ(run.max_abs_translation, 0.0);
  }
  MoverRun before = WithoutSeparation(150, [](int) { return Still(); }, MoverScene(Wall(700, 4, 0.6, 1), {Head(0.55)}));
  Print("head 0.55, one motion", before);
  EXPECT_LT(before.models["static"], 150);  // what the border corrects
}

// A head filling 30 % of the frame over a dark room: no background tracks
// but a small lit object in the frame's corner (a candle: 8 points 4 m
// away). The head's turn and nod
// is the only coherent motion of most intervals and holds too little of the
// frame's edge to be confirmed (border support below one half); the corner
// stays still where that turn would move it, so the shot is a still camera
// before a moving subject. Without the corner nothing contradicts the
// motion (an object turned before an empty background is the same two-view
// geometry as a camera orbiting it): the motion stays, flagged by its
// border support (shot_quality.h).
std::vector<Eigen::Vector3d> CornerLight(int n, unsigned seed) {
  std::vector<Eigen::Vector3d> pts = RandomPoints(n, 4, 4, 0.015, seed);  // +-12 x +-7 px
  // Centred 40 px inside the top-left corner.
  const Eigen::Vector3d corner((40 - 0.5 * kW) / kFocal * 4, (0.5 * kH - 40) / kFocal * 4, 0);
  for (Eigen::Vector3d& p : pts) p += corner;
  return pts;
}

TEST(TrackEstimatorMovers, HeadOverADarkRoomWithAStillCornerIsAStillCamera) {
  MoverRun still = Simulate(
      150, [](int) { return Still(); }, MoverScene(CornerLight(8, 3), {Head(0.3)}));
  Print("head over a dark room, lit corner", still);
  EXPECT_EQ(still.models["static"], 150);
  EXPECT_EQ(still.mean_rot_err_deg, 0.0);
  EXPECT_EQ(still.max_abs_translation, 0.0);
  MoverRun dark = Simulate(
      150, [](int) { return Still(); }, MoverScene({}, {Head(0.3)}));
  Print("head over a dark room", dark);
  EXPECT_LT(dark.models["static"], 150);
  EXPECT_GT(dark.mean_rot_err_deg, 1.0);
}

// A person (ellipsoid 25 x 90 x 20 cm) at `depth` m walking along x at
// `speed` m per frame from x0.
Mover Person(double depth, double x0, double speed, unsigned seed, double size = 1, double density = 1) {
  Mover p;
  p.radii = size * Eigen::Vector3d(0.25, 0.9, 0.2);
  p.pose = [=](int i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(x0 + speed * i, -0.2, -depth);
    return pose;
  };
  p.surface = SurfacePoints(p.radii, static_cast<int>(2000 * density * size * size / (depth * depth)), seed);
  return p;
}

// Two people crossing (in opposite directions, 2.2 m away) during a pan and
// during a traveling: the camera's motion should be the same as without
// them. Not met yet (docs/estimate.md, "What it does not model"): the
// people's horizontal motion is epipolar-consistent with the pan plus a
// small sideways move, or with the traveling, so the majority's motion
// nests the border's and only a still border is preferred; the window then
// bends around them (pan 1.6 deg, traveling 8.5 deg of rotation error).
TEST(TrackEstimatorMovers, DISABLED_PeopleCrossingDuringAPanOrATravelingDoNotChangeIt) {
  const auto people = [] { return std::vector<Mover>{Person(2.2, -1.6, 0.05, 3, 1, 2), Person(2.4, 1.4, -0.045, 4, 1, 2)}; };
  const auto pan_scene = RandomPoints(2500, 5, 30, 1.2, 2);
  const auto pan = [](int i) { return Pan(i, 90, 20); };
  const MoverRun pan_alone = Simulate(90, pan, MoverScene(pan_scene, {}));
  const MoverRun pan_people = Simulate(90, pan, MoverScene(pan_scene, people()));
  Print("pan alone", pan_alone);
  Print("pan with people", pan_people);
  Print("pan with people, one motion", WithoutSeparation(90, pan, MoverScene(pan_scene, people())));
  EXPECT_GT(pan_people.mover_share_percent, 25);
  EXPECT_EQ(pan_people.max_abs_translation, 0.0);
  EXPECT_LT(pan_people.mean_rot_err_deg, pan_alone.mean_rot_err_deg + 0.05);

  const auto travel_scene = RandomPoints(1500, 3, 12, 1.2, 3);
  const auto travel = [](int i) {
    SceneCamera c;
    c.center = Eigen::Vector3d(2.0 * Ease(i, 90), 0, 0);
    c.focal_px = kFocal;
    return c;
  };
  const MoverRun travel_alone = Simulate(90, travel, MoverScene(travel_scene, {}));
  const MoverRun travel_people = Simulate(90, travel, MoverScene(travel_scene, people()));
  Print("traveling alone", travel_alone);
  Print("traveling with people", travel_people);
  Print("traveling with people, one motion", WithoutSeparation(90, travel, MoverScene(travel_scene, people())));
  EXPECT_GT(travel_people.mover_share_percent, 20);
  EXPECT_LT(travel_people.mean_rot_err_deg, travel_alone.mean_rot_err_deg + 0.05);
  const Eigen::Vector3d end = travel_people.end_center;
  EXPECT_GT(end.x(), 0);
  EXPECT_LT(std::abs(end.y()) + std::abs(end.z()), 0.05 * end.x());
}

// A crowd of small walkers (6-12 m away, either way) in front of a still
// camera and a far background.
TEST(TrackEstimatorMovers, CrowdInFrontOfAStillCamera) {
  std::vector<Mover> crowd;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 20; ++k) {
    const double depth = 4 + 6 * u(rng);
    const double speed = (k % 2 ? 1 : -1) * (0.04 + 0.02 * u(rng));
    crowd.push_back(Person(depth, (u(rng) - 0.5) * 0.9 * depth, speed, 20 + k, 0.9, 3));
  }
  MoverRun run = Simulate(120, [](int) { return Still(); }, MoverScene(Wall(900, 20, 0.6, 9), crowd));
  Print("crowd", run);
  Print("crowd, one motion", WithoutSeparation(120, [](int) { return Still(); }, MoverScene(Wall(900, 20, 0.6, 9), crowd)));
  EXPECT_GT(run.mover_share_percent, 35);
  // The intervals where the majority's motion is a turn of ~0 (its own
  // fit to the background) keep it: no translation, no rotation.
  EXPECT_GT(run.models["static"], 90);
  EXPECT_EQ(run.models["general"] + run.models["general+zoom"], 0);
  EXPECT_LE(run.mean_rot_err_deg, 0.3);
  EXPECT_EQ(run.max_abs_translation, 0.0);
}

// The camera pans to keep a walker centred: the walker is still in the
// picture, the background slides. The background is the camera's evidence.
TEST(TrackEstimatorMovers, CameraFollowingASubjectKeepsItsPan) {
  const auto follow = [](int i) {
    SceneCamera c;
    PanTiltRoll ptr;
    ptr.pan_deg = -std::atan((-1.5 + 0.035 * i) / 2.5) * 180 / kPi;
    c.world_from_cam = QuaternionFromPanTiltRoll(ptr);
    c.focal_px = kFocal;
    return c;
  };
  const MoverScene scene(RandomPoints(2500, 6, 30, 1.2, 5), {Person(2.5, -1.5, 0.035, 6, 1.2)});
  MoverRun run = Simulate(90, follow, scene);
  const MoverRun before = WithoutSeparation(90, follow, scene);
  Print("follow", run);
  Print("follow, one motion", before);
  EXPECT_GT(run.mover_share_percent, 25);
  EXPECT_EQ(run.max_abs_translation, 0.0);
  EXPECT_GT(run.models["rotation"], 60);
  EXPECT_LT(run.mean_rot_err_deg, before.mean_rot_err_deg + 0.02);
}

// A crane-like move (a pan while the camera slides sideways) past a near
// object: real parallax, one rigid scene. Nothing to separate: the same
// path as with one motion.
TEST(TrackEstimatorMovers, PanWithParallaxIsUnchanged) {
  const auto arc = [](int i) {
    SceneCamera c = Pan(i, 90, 15);
    c.center = Eigen::Vector3d(0.6 * Ease(i, 90), 0, 0);
    return c;
  };
  std::vector<Eigen::Vector3d> pts = RandomPoints(1500, 4, 20, 1.0, 12);
  const auto near = RandomPoints(300, 1.4, 1.7, 0.15, 13);
  pts.insert(pts.end(), near.begin(), near.end());
  MoverRun run = Simulate(90, arc, MoverScene(pts, {}));
  const MoverRun before = WithoutSeparation(90, arc, MoverScene(pts, {}));
  Print("pan with parallax", run);
  Print("pan with parallax, one motion", before);
  EXPECT_EQ(run.models["general"] + run.models["general+zoom"], 90);
  EXPECT_LT(run.mean_rot_err_deg, before.mean_rot_err_deg + 0.01);
  EXPECT_GT(run.end_center.x(), 0);
}

}  // namespace
}  // namespace hapcine
