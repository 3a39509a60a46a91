#include "estimate/bundle/bundle_adjustment.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

namespace hapcine {
namespace {

// Synthetic window in OpenCV axes: `n` cameras, `m` points.
struct Window {
  std::vector<BaCamera> truth, init;
  std::vector<BaPoint> points_truth, points_init;
  std::vector<BaObservation> obs;
};

Window Pan(int n, double step_deg, double focal, double far_fraction, bool translate, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5), d(2, 8);
  std::normal_distribution<double> g(0, 0.3 / 960);
  Window w;
  for (int i = 0; i < n; ++i) {
    BaCamera c;
    c.world_from_cam = Eigen::AngleAxisd(i * step_deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(0.3 * i * step_deg * M_PI / 180, Eigen::Vector3d::UnitX());
    c.center = translate ? Eigen::Vector3d(0.1 * i, 0, 0) : Eigen::Vector3d::Zero();
    c.log_focal = std::log(focal);
    w.truth.push_back(c);
  }
  for (int j = 0; j < 300; ++j) {
    const bool far = u(rng) + 0.5 < far_fraction;
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng) * 1.2, u(rng) * 0.6, 1).normalized();
    BaPoint p;
    p.anchor = Eigen::Vector3d::Zero();
    p.homogeneous << dir, far ? 0.0 : 1.0 / d(rng);
    p.homogeneous.normalize();
    w.points_truth.push_back(p);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 300; ++j) {
      const BaPoint& p = w.points_truth[j];
      const Eigen::Vector3d v = p.homogeneous.head<3>() + p.homogeneous(3) * (p.anchor - w.truth[i].center);
      const Eigen::Vector3d pc = w.truth[i].world_from_cam.conjugate() * v;
      if (pc.z() <= 0) continue;
      const Eigen::Vector2d uv = focal * pc.hnormalized() + Eigen::Vector2d(g(rng), g(rng));
      if (std::abs(uv.x()) > 0.5 || std::abs(uv.y()) > 0.3) continue;
      w.obs.push_back({i, j, uv});
    }
  }
  return w;
}

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b) * 180 / M_PI;
}

TEST(BundleAdjustment, PanRecoversFocalAndRotationsWithZeroTranslation) {
  const double focal = 1.3;
  Window w = Pan(12, 1.5, focal, 0.5, false, 1);
  std::vector<BaCamera> cams = w.truth;
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0, 0.01);
  for (int i = 0; i < 12; ++i) {
    cams[i].log_focal = std::log(1.07);  // 50 degree prior, 20 % off
    if (i > 0) {
      cams[i].world_from_cam = cams[i].world_from_cam * Eigen::Quaterniond(Eigen::AngleAxisd(g(rng), Eigen::Vector3d::UnitY()));
      cams[i].center_source = i - 1;  // rotation model: one shared centre
      cams[i].focal_source = i - 1;
    }
  }
  cams[0].fixed = true;
  std::vector<BaPoint> pts;
  for (int j = 0; j < 300; ++j) {  // bearings only, from the first observation
    BaPoint p;
    p.homogeneous << (Eigen::Vector3d(0, 0, 1)), 0;
    pts.push_back(p);
  }
  for (const auto& o : w.obs) {
    if (o.camera != 0 && pts[o.point].homogeneous.head<3>() != Eigen::Vector3d(0, 0, 1)) continue;
    const Eigen::Vector3d b = cams[o.camera].world_from_cam * Eigen::Vector3d(o.u.x() / 1.07, o.u.y() / 1.07, 1);
    pts[o.point].homogeneous << b.normalized(), 0;
  }
  BaOptions opt;
  opt.use_depth = false;
  opt.focal_prior_log = std::log(1.07);
  const BaSummary s = SolveBundle(&cams, &pts, w.obs, opt);
  ASSERT_TRUE(s.success);
  EXPECT_NEAR(std::exp(cams[5].log_focal) / focal, 1.0, 0.003);
  for (int i = 0; i < 12; ++i) {
    EXPECT_LT(AngleDeg(cams[i].world_from_cam, w.truth[i].world_from_cam), 0.02) << i;
    EXPECT_EQ(cams[i].center, Eigen::Vector3d::Zero());  // exactly
  }
  EXPECT_LT(s.rms_after * 960, 0.5);
}

TEST(BundleAdjustment, InverseDepthWithPointsAtInfinityAndTranslation) {
  const double focal = 1.1;
  Window w = Pan(8, 0.5, focal, 0.4, true, 3);
  std::vector<BaCamera> cams = w.truth;
  std::vector<BaPoint> pts = w.points_truth;
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0, 0.02);
  for (int i = 2; i < 8; ++i) cams[i].center += Eigen::Vector3d(g(rng), g(rng), g(rng));
  for (auto& p : pts) {
    p.homogeneous(3) *= 1.3;  // all depths wrong
    p.homogeneous.normalize();
  }
  cams[0].fixed = cams[1].fixed = true;  // gauge incl. scale
  BaOptions opt;
  opt.use_depth = true;
  opt.fix_first_focal = true;
  opt.focal_prior_log = std::log(focal);
  const BaSummary s = SolveBundle(&cams, &pts, w.obs, opt);
  ASSERT_TRUE(s.success);
  for (int i = 0; i < 8; ++i) {
    EXPECT_LT((cams[i].center - w.truth[i].center).norm(), 0.01) << i;
    EXPECT_LT(AngleDeg(cams[i].world_from_cam, w.truth[i].world_from_cam), 0.05) << i;
  }
  int at_infinity = 0;
  for (size_t j = 0; j < pts.size(); ++j) {
    ASSERT_TRUE(pts[j].homogeneous.allFinite());
    if (w.points_truth[j].homogeneous(3) == 0) {
      ++at_infinity;
      EXPECT_LT(std::abs(pts[j].homogeneous(3)), 0.02);
    }
  }
  EXPECT_GT(at_infinity, 50);
}

// Translating window where one interval is rotation-only (camera 4 shares
// camera 3's centre): rotation and centre are one block where a camera owns
// both, two where the sharing splits them; the soft scale gauge may join a
// merged and a split centre.
TEST(BundleAdjustment, MixedSharingWithMergedAndSplitPoseBlocks) {
  const double focal = 1.1;
  Window truth = Pan(8, 0.7, focal, 0.3, true, 5);
  // Rebuild with camera 4 at camera 3's centre (re-observe every point).
  for (int i = 4; i < 8; ++i) truth.truth[i].center = Eigen::Vector3d(0.1 * (i - 1), 0, 0);
  truth.obs.clear();
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 300; ++j) {
      const BaPoint& p = truth.points_truth[j];
      const Eigen::Vector3d v = p.homogeneous.head<3>() + p.homogeneous(3) * (p.anchor - truth.truth[i].center);
      const Eigen::Vector3d pc = truth.truth[i].world_from_cam.conjugate() * v;
      if (pc.z() <= 0) continue;
      const Eigen::Vector2d uv = focal * pc.hnormalized();
      if (std::abs(uv.x()) > 0.5 || std::abs(uv.y()) > 0.3) continue;
      truth.obs.push_back({i, j, uv});
    }
  for (const auto& [scale_a, scale_b] : {std::pair<int, int>{1, 2}, {3, 5}}) {
    std::vector<BaCamera> cams = truth.truth;
    std::vector<BaPoint> pts = truth.points_truth;
    std::mt19937 rng(6);
    std::normal_distribution<double> g(0, 0.01);
    for (int i = 1; i < 8; ++i) {
      cams[i].center += Eigen::Vector3d(g(rng), g(rng), g(rng));
      cams[i].world_from_cam = cams[i].world_from_cam * Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * g(rng), Eigen::Vector3d::UnitY()));
      cams[i].focal_source = i - 1;
    }
    cams[4].center_source = 3;
    cams[4].center = cams[3].center;
    for (auto& p : pts) {
      p.homogeneous(3) *= 1.2;
      p.homogeneous.normalize();
    }
    cams[0].fixed = true;
    BaOptions opt;
    opt.use_depth = true;
    opt.fix_first_focal = true;
    opt.scale_a = scale_a;
    opt.scale_b = scale_b;
    opt.scale_distance = (truth.truth[scale_b].center - truth.truth[scale_a].center).norm();
    const BaSummary s = SolveBundle(&cams, &pts, truth.obs, opt);
    ASSERT_TRUE(s.success) << scale_a;
    EXPECT_LT(s.rms_after * 960, 0.01) << scale_a;
    for (int i = 0; i < 8; ++i) {
      EXPECT_LT((cams[i].center - truth.truth[i].center).norm(), 1e-3) << scale_a << " camera " << i;
      EXPECT_LT(AngleDeg(cams[i].world_from_cam, truth.truth[i].world_from_cam), 0.01) << scale_a << " camera " << i;
    }
    EXPECT_EQ(cams[4].center, cams[3].center);  // shared block, exactly
  }
}

// The soft scale gauge on an interval whose length is wrong (half the
// truth), in a window whose scale the held first and last cameras pin:
// tight (the default) it holds that length against the observations; loose
// (scale_weight 1, shots of stills) the interval follows the window.
TEST(BundleAdjustment, LooseScaleGaugeLetsTheIntervalFollowTheWindow) {
  const double focal = 1.1;
  const Window w = Pan(8, 0.5, focal, 0.0, true, 7);
  const double truth = (w.truth[1].center - w.truth[0].center).norm();
  auto solved_length = [&](double scale_weight) {
    std::vector<BaCamera> cams = w.truth;
    std::vector<BaPoint> pts = w.points_truth;
    cams[0].fixed = cams[7].fixed = true;
    BaOptions opt;
    opt.use_depth = true;
    opt.fix_first_focal = true;
    opt.scale_a = 0;
    opt.scale_b = 1;
    opt.scale_distance = 0.5 * truth;
    opt.scale_weight = scale_weight;
    const BaSummary s = SolveBundle(&cams, &pts, w.obs, opt);
    EXPECT_TRUE(s.success);
    return (cams[1].center - cams[0].center).norm();
  };
  EXPECT_NEAR(solved_length(1e3), 0.5 * truth, 0.05 * truth);
  EXPECT_NEAR(solved_length(1.0), truth, 0.02 * truth);
}

TEST(BundleAdjustment, PoseOnlyRespectsFreedoms) {
  Window w = Pan(3, 2, 1.2, 1.0, false, 5);
  BaCamera cam = w.truth[2];
  cam.world_from_cam = w.truth[1].world_from_cam;
  std::vector<BaObservation> obs;
  for (const auto& o : w.obs)
    if (o.camera == 2) obs.push_back(o);
  BaOptions opt;
  opt.use_depth = false;
  PoseFreedoms fr;
  fr.rotation = true;
  const BaSummary s = SolvePose(&cam, fr, w.points_truth, obs, opt);
  ASSERT_TRUE(s.success);
  EXPECT_LT(AngleDeg(cam.world_from_cam, w.truth[2].world_from_cam), 0.01);
  EXPECT_EQ(cam.center, Eigen::Vector3d::Zero());
  EXPECT_EQ(cam.log_focal, std::log(1.2));
}

TEST(BundleAdjustment, EmptyProblemFailsCleanly) {
  std::vector<BaCamera> cams(1);
  std::vector<BaPoint> pts;
  const BaSummary s = SolveBundle(&cams, &pts, {}, BaOptions{});
  EXPECT_FALSE(s.success);
}

}  // namespace
}  // namespace hapcine
