#include "estimate/window/window_freedoms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hapcine {
namespace {

// Three cameras at the origin looking along +z (OpenCV axes), points as
// bearings, observed by every camera (or by the cameras in [first, last]).
struct Scene {
  std::vector<BaCamera> cams = std::vector<BaCamera>(3);
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
};

Scene MakeScene(int n_points, double noise, unsigned seed, int first = 0, int last = 2) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::normal_distribution<double> e(0, noise);
  for (int k = 0; k < n_points; ++k) {
    BaPoint p;
    p.homogeneous = Eigen::Vector4d(u(rng), u(rng), 1, 0).normalized();
    for (int c = first; c <= last; ++c) {
      const Eigen::Vector2d x = p.homogeneous.head<2>() / p.homogeneous(2);
      s.obs.push_back({c, k, x + Eigen::Vector2d(e(rng), e(rng))});
    }
    s.points.push_back(p);
  }
  return s;
}

TEST(CompareFreedoms, EqualFitsDoNotPayForTheFreedoms) {
  const Scene s = MakeScene(100, 0.5 / 960, 1);
  const FreedomEvidence ev =
      CompareFreedoms(s.cams, s.points, s.cams, s.points, s.obs, {0, 0, 1}, {0, 0, 0}, 0.25 / 960);
  EXPECT_DOUBLE_EQ(ev.chi2_with, ev.chi2_without);
  EXPECT_FALSE(ev.PaysOff());
  EXPECT_EQ(ev.translation_dropped, 1);
  EXPECT_EQ(ev.informed_points, 100);  // every point is seen across interval 1 -> 2
  // k = 3 (one centre) + 100 (depths), m = 2 * 300 observations.
  EXPECT_NEAR(ev.penalty, 103 * std::log(600.0), 1e-9);
  EXPECT_NEAR(ev.sigma * 960, 0.5, 0.1);  // measured from the residuals, above the floor
}

TEST(CompareFreedoms, AClearlyBetterFitPaysForThem) {
  const Scene s = MakeScene(100, 0.3 / 960, 2);
  std::vector<BaCamera> worse = s.cams;
  // One camera turned by ~0.1 degree: ~2 px at 960 px of systematic error.
  worse[2].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitY()));
  const FreedomEvidence ev =
      CompareFreedoms(s.cams, s.points, worse, s.points, s.obs, {0, 0, 1}, {0, 0, 1}, 0.25 / 960);
  EXPECT_GT(ev.chi2_without, ev.chi2_with + ev.penalty);
  EXPECT_TRUE(ev.PaysOff());
  EXPECT_EQ(ev.zoom_dropped, 1);
}

TEST(BlurSigmas, GrowWithEachPointsImageSpeedToItsNeighbouringCameras) {
  // One point seen by cameras at frames 0, 1 and 3, moving 0.1 (frame 0 -> 1)
  // then 0.1 in two frames; a second point seen once.
  std::vector<BaObservation> obs = {{0, 0, {0.0, 0.0}}, {1, 0, {0.1, 0.0}}, {2, 0, {0.2, 0.0}},
                                    {1, 1, {0.3, 0.3}}};
  const std::vector<double> b = BlurSigmas(obs, {0, 1, 3}, 0.04);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_NEAR(b[0], 0.04 * 0.1, 1e-12);   // its only neighbour: 0.1 per frame
  EXPECT_NEAR(b[1], 0.04 * 0.1, 1e-12);   // the faster of 0.1 and 0.05 per frame
  EXPECT_NEAR(b[2], 0.04 * 0.05, 1e-12);  // 0.1 over two frames
  EXPECT_EQ(b[3], 0.0);                   // seen once: no speed
  EXPECT_EQ(BlurSigmas(obs, {0, 1, 3}, 0.0), std::vector<double>(4, 0.0));
  // Two cameras at the same frame (a degenerate window) give no speed, not inf.
  EXPECT_EQ(BlurSigmas(obs, {0, 0, 0}, 0.04)[0], 0.0);
}

TEST(CompareFreedoms, BlurNoiseDiscountsMisfitOnFastMovingObservations) {
  // The simpler fit is 2 px off on camera 2, where the points move 100 px a
  // frame: at 0.04 px per px/frame that is 4 px of blur noise, so the misfit
  // no longer pays for a centre and 100 depths; without the blur term it does.
  const Scene s = MakeScene(100, 0.3 / 960, 2);
  std::vector<BaCamera> worse = s.cams;
  worse[2].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitY()));
  std::vector<double> blur(s.obs.size(), 0.0);
  for (size_t i = 0; i < s.obs.size(); ++i)
    if (s.obs[i].camera == 2) blur[i] = 0.04 * 100.0 / 960;
  const FreedomEvidence sharp =
      CompareFreedoms(s.cams, s.points, worse, s.points, s.obs, {0, 0, 1}, {0, 0, 0}, 0.25 / 960);
  const FreedomEvidence blurred =
      CompareFreedoms(s.cams, s.points, worse, s.points, s.obs, {0, 0, 1}, {0, 0, 0}, 0.25 / 960, blur);
  EXPECT_TRUE(sharp.PaysOff());
  EXPECT_FALSE(blurred.PaysOff());
  EXPECT_LT(blurred.chi2_without - blurred.chi2_with, 0.1 * (sharp.chi2_without - sharp.chi2_with));
}

TEST(CompareFreedoms, OnlyPointsSeenAcrossADroppedIntervalCountDepths) {
  Scene s = MakeScene(10, 0, 3, 0, 1);       // seen by cameras 0-1 only
  const Scene t = MakeScene(20, 0, 4, 1, 2);  // seen by cameras 1-2
  for (BaObservation o : t.obs) {
    o.point += 10;
    s.obs.push_back(o);
  }
  s.points.insert(s.points.end(), t.points.begin(), t.points.end());
  const FreedomEvidence ev =
      CompareFreedoms(s.cams, s.points, s.cams, s.points, s.obs, {0, 1, 0}, {0, 0, 0}, 0.25 / 960);
  EXPECT_EQ(ev.informed_points, 10);  // interval 0 -> 1 is the dropped one
  // Noise-free: every error is zero, sigma is the floor, nothing to gain.
  EXPECT_DOUBLE_EQ(ev.sigma, 0.25 / 960);
  EXPECT_DOUBLE_EQ(ev.chi2_with, 0.0);
  EXPECT_FALSE(ev.PaysOff());
}

TEST(CompareFreedoms, PointsBehindTheCameraCountAsCappedOutliersWithoutNaN) {
  Scene s = MakeScene(50, 0.3 / 960, 5);
  std::vector<BaCamera> turned = s.cams;
  turned[1].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(3.1, Eigen::Vector3d::UnitY()));
  const FreedomEvidence ev =
      CompareFreedoms(s.cams, s.points, turned, s.points, s.obs, {0, 1, 0}, {0, 0, 0}, 0.25 / 960);
  EXPECT_TRUE(std::isfinite(ev.chi2_without));
  EXPECT_NEAR(ev.chi2_without - ev.chi2_with, 9.0 * 50 - [&] {
    double c = 0;  // camera 1's share of chi2_with
    for (size_t i = 0; i < s.obs.size(); ++i)
      if (s.obs[i].camera == 1) {
        const double e = (s.obs[i].u - s.points[s.obs[i].point].homogeneous.head<2>() /
                                           s.points[s.obs[i].point].homogeneous(2)).norm();
        c += std::min(e * e / (ev.sigma * ev.sigma), 9.0);
      }
    return c;
  }(), 1e-6);
  EXPECT_TRUE(ev.PaysOff());
}

TEST(CompareFreedoms, ANegligibleZoomIsDroppedEvenWhenItFitsBetter) {
  const Scene s = MakeScene(100, 0.3 / 960, 6);
  std::vector<BaCamera> with = s.cams;
  with[2].log_focal = 0.0005;  // a 0.05 % zoom
  std::vector<BaCamera> worse = s.cams;
  worse[2].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitY()));
  // The zoom-only test: the fit is much better with the zoom, yet it is no zoom.
  FreedomEvidence ev = CompareFreedoms(with, s.points, worse, s.points, s.obs, {0, 0, 0}, {0, 0, 1}, 0.25 / 960);
  EXPECT_NEAR(ev.zoom_change, 0.0005, 1e-12);
  EXPECT_GT(ev.chi2_without - ev.chi2_with, ev.penalty);
  EXPECT_FALSE(ev.PaysOff());
  // A 1 % zoom that fits better stays.
  with[2].log_focal = 0.01;
  ev = CompareFreedoms(with, s.points, worse, s.points, s.obs, {0, 0, 0}, {0, 0, 1}, 0.25 / 960);
  EXPECT_NEAR(ev.zoom_change, 0.01, 1e-12);
  EXPECT_EQ(ev.PaysOff(), ev.chi2_without - ev.chi2_with > ev.penalty);
  // With translation in the test the zoom's size does not matter.
  with[2].log_focal = 0;
  ev = CompareFreedoms(s.cams, s.points, worse, s.points, s.obs, {0, 0, 1}, {0, 0, 1}, 0.25 / 960);
  EXPECT_TRUE(ev.PaysOff());
}

TEST(ComparePromotion, PaysOnlyForAClearlyBetterFitAtTwoParametersPerKeyframe) {
  const Scene s = MakeScene(100, 0.3 / 960, 7);
  PromotionEvidence ev = ComparePromotion(s.cams, s.points, s.cams, s.points, s.obs, 2, 0.25 / 960);
  EXPECT_DOUBLE_EQ(ev.chi2_current, ev.chi2_promoted);
  EXPECT_NEAR(ev.penalty, 2 * 2 * std::log(600.0), 1e-9);  // a centre gained, a focal lost; m = 300
  EXPECT_FALSE(ev.PaysOff());
  std::vector<BaCamera> worse = s.cams;
  worse[2].world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitY()));
  ev = ComparePromotion(s.cams, s.points, worse, s.points, s.obs, 2, 0.25 / 960);
  EXPECT_GT(ev.chi2_current, ev.chi2_promoted + ev.penalty);
  EXPECT_TRUE(ev.PaysOff());
  // The other way round: the promoted solve fits worse, nothing to pay for.
  ev = ComparePromotion(worse, s.points, s.cams, s.points, s.obs, 2, 0.25 / 960);
  EXPECT_FALSE(ev.PaysOff());
}

}  // namespace
}  // namespace hapcine

namespace hapcine {
namespace {

TEST(ChooseFocalCandidate, TakesTheBestUnlessTheFreedomsDoNotPay) {
  const double px = 1.0 / 960;
  const std::vector<double> constant(400, 2.0 * px);  // 2 px everywhere
  const std::vector<double> better(400, 0.5 * px), same(400, 2.0 * px), worse(400, 3.0 * px);
  // A clear gain over 400 observations pays for 5 focals; the better of two wins.
  EXPECT_EQ(ChooseFocalCandidate(constant, {worse, better}, {0, 0, 0}, 5, 0.25 * px), 1);
  // No gain: the penalty keeps the constant focal.
  EXPECT_EQ(ChooseFocalCandidate(constant, {same}, {0, 0}, 5, 0.25 * px), -1);
  // The occlusion order rules the better candidate out: the other is no gain.
  EXPECT_EQ(ChooseFocalCandidate(constant, {same, better}, {0, 0, 1}, 5, 0.25 * px), -1);
  // It rules the constant solve out: the best remaining is taken, gain or not.
  EXPECT_EQ(ChooseFocalCandidate(constant, {worse}, {1, 0}, 5, 0.25 * px), 0);
  // Nothing to choose from.
  EXPECT_EQ(ChooseFocalCandidate(constant, {}, {0}, 5, 0.25 * px), -1);
  EXPECT_EQ(ChooseFocalCandidate(constant, {better}, {0, 1}, 5, 0.25 * px), -1);
}

}  // namespace
}  // namespace hapcine
