#include "estimate/bundle/robust_bundle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hapcine {
namespace {

constexpr double kPx = 1.0 / kReferenceWidthPx;  // one reference pixel, normalised units

// A pan on a tripod (OpenCV axes): 8 cameras 2 degrees apart, focal 1 held,
// 120 points as bearings seen by every camera, 0.2 px of noise. Camera 0
// is the gauge; the others start 0.3 degrees off.
struct Pan {
  std::vector<BaCamera> truth, cams;
  std::vector<BaPoint> truth_points, points;
  std::vector<BaObservation> obs;
  BaOptions options;
};

Pan MakePan(unsigned seed) {
  Pan w;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::normal_distribution<double> noise(0, 0.2 * kPx);
  for (int i = 0; i < 8; ++i) {
    BaCamera c;
    c.world_from_cam = Eigen::AngleAxisd(i * 2.0 * M_PI / 180, Eigen::Vector3d::UnitY());
    if (i > 0) c.center_source = c.focal_source = i - 1;
    w.truth.push_back(c);
    c.world_from_cam = c.world_from_cam * Eigen::AngleAxisd(i > 0 ? 0.3 * M_PI / 180 : 0, Eigen::Vector3d::UnitX());
    c.fixed = i == 0;
    w.cams.push_back(c);
  }
  for (int k = 0; k < 120; ++k) {
    BaPoint p;
    p.homogeneous << Eigen::Vector3d(u(rng) + 0.1, u(rng), 1).normalized(), 0;
    w.truth_points.push_back(p);
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d v = w.truth[i].world_from_cam.conjugate() * p.homogeneous.head<3>();
      w.obs.push_back({i, k, v.hnormalized() + Eigen::Vector2d(noise(rng), noise(rng))});
    }
  }
  w.points = w.truth_points;
  w.options.use_depth = false;
  w.options.fix_first_focal = true;
  return w;
}

// Largest angle between the cameras of a and b, degrees.
double MaxAngleDeg(const std::vector<BaCamera>& a, const std::vector<BaCamera>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, a[i].world_from_cam.angularDistance(b[i].world_from_cam) * 180 / M_PI);
  return worst;
}

// The pan solved by plain SolveBundle on `obs` (what the robust rounds
// should reach when `obs` are the clean observations).
std::vector<BaCamera> Reference(const Pan& w, const std::vector<BaObservation>& obs) {
  std::vector<BaCamera> cams = w.cams;
  std::vector<BaPoint> points = w.points;
  EXPECT_TRUE(SolveBundle(&cams, &points, obs, w.options).success);
  return cams;
}

TEST(SolveDroppingOutliers, DropsGrossOutliersAndRecoversThePan) {
  Pan w = MakePan(1);
  const size_t total = w.obs.size();
  std::vector<BaObservation> clean;
  for (size_t i = 0; i < w.obs.size(); ++i)
    if (i % 37 != 5 || i >= 37 * 6) clean.push_back(w.obs[i]);
  const std::vector<BaCamera> reference = Reference(w, clean);
  for (int j = 0; j < 6; ++j) w.obs[37 * j + 5].u.x() += 15 * kPx;  // six observations 15 px off
  const BaSummary s = SolveDroppingOutliers(w.options, &w.cams, &w.points, &w.obs);
  ASSERT_TRUE(s.success);
  EXPECT_EQ(w.obs.size(), total - 6);
  EXPECT_EQ(s.num_observations, static_cast<int>(total - 6));
  EXPECT_LT(s.rms_after, 0.4 * kPx);
  EXPECT_LT(MaxAngleDeg(w.cams, reference), 1e-4);  // as if the outliers had never been there
  EXPECT_LT(MaxAngleDeg(w.cams, w.truth), 0.03);     // the noise's share
}

TEST(SolveDroppingOutliers, CleanDataKeepsEveryObservation) {
  Pan w = MakePan(2);
  const size_t total = w.obs.size();
  const std::vector<BaCamera> reference = Reference(w, w.obs);
  const BaSummary s = SolveDroppingOutliers(w.options, &w.cams, &w.points, &w.obs);
  ASSERT_TRUE(s.success);
  EXPECT_EQ(w.obs.size(), total);
  EXPECT_LT(MaxAngleDeg(w.cams, reference), 1e-4);
}

TEST(SolveDroppingOutliers, NoObservationsIsAFailureNotACrash) {
  Pan w = MakePan(3);
  w.obs.clear();
  const BaSummary s = SolveDroppingOutliers(w.options, &w.cams, &w.points, &w.obs);
  EXPECT_FALSE(s.success);
}

TEST(DropInconsistentTracks, DropsASlidingTrackWholeAndKeepsTheRigidOnes) {
  Pan w = MakePan(4);
  // Track 7 slides: 0.5 px more to the right in every camera (a corner
  // moving along a silhouette), each observation within 3.5 px of the rigid
  // point and never a gross outlier.
  for (auto& o : w.obs)
    if (o.point == 7) o.u.x() += 0.5 * kPx * o.camera;
  const std::vector<BaObservation> all = w.obs;
  std::vector<BaObservation> rigid;
  for (const auto& o : all)
    if (o.point != 7) rigid.push_back(o);
  const std::vector<BaCamera> reference = Reference(w, rigid);
  BaSummary s = SolveDroppingOutliers(w.options, &w.cams, &w.points, &w.obs);
  ASSERT_TRUE(s.success);
  std::vector<BaObservation> kept;
  DropInconsistentTracks(w.options, 0.2 * kPx, &w.cams, &w.points, all, &kept, &s);
  int of_sliding = 0;
  for (const auto& o : kept) of_sliding += o.point == 7;
  EXPECT_EQ(of_sliding, 0);
  EXPECT_GE(kept.size(), all.size() - 8 - 8 * 3);  // the sliding track, and a few noisy ones at most
  EXPECT_LT(MaxAngleDeg(w.cams, reference), 0.002);
}

TEST(DropInconsistentTracks, TooFewObservationsKeepsThemAll) {
  Pan w = MakePan(5);
  std::vector<BaObservation> few(w.obs.begin(), w.obs.begin() + 8);  // one point in 8 cameras
  std::vector<BaObservation> kept;
  BaSummary s;
  DropInconsistentTracks(w.options, 0.2 * kPx, &w.cams, &w.points, few, &kept, &s);
  EXPECT_EQ(kept.size(), few.size());
}

}  // namespace
}  // namespace hapcine
