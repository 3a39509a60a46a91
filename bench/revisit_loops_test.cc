#include "bench/revisit_loops.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine {
namespace {

constexpr double kDeg = M_PI / 180;

Eigen::Quaterniond Yaw(double deg) { return Eigen::Quaterniond(Eigen::AngleAxisd(deg * kDeg, Eigen::Vector3d::UnitY())); }

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.conjugate() * b).angle() / kDeg;
}

// An orbit of `views` views, `step_deg` apart about the vertical axis, looking inwards.
std::vector<Eigen::Quaterniond> Orbit(int views, double step_deg) {
  std::vector<Eigen::Quaterniond> q;
  for (int k = 0; k < views; ++k) q.push_back(Yaw(k * step_deg));
  return q;
}

// The same orbit as a drifting estimator solves it: every step off by a
// small turn about an axis of the camera (the bias of aging tracks).
std::vector<Eigen::Quaterniond> Drifted(const std::vector<Eigen::Quaterniond>& truth, double drift_deg) {
  std::vector<Eigen::Quaterniond> q{truth[0]};
  const Eigen::Quaterniond bias(Eigen::AngleAxisd(drift_deg * kDeg, Eigen::Vector3d(1, 1, 0).normalized()));
  for (size_t k = 1; k < truth.size(); ++k) q.push_back(q.back() * (truth[k - 1].conjugate() * truth[k]) * bias);
  return q;
}

double MeanErrorDeg(const std::vector<Eigen::Quaterniond>& a, const std::vector<Eigen::Quaterniond>& b) {
  double sum = 0;
  for (size_t k = 0; k < a.size(); ++k) sum += AngleDeg(a[k], b[k]);
  return sum / a.size();
}

std::vector<RevisitLink> TrueLinks(const std::vector<Eigen::Quaterniond>& truth,
                                   const std::vector<RevisitPair>& pairs) {
  std::vector<RevisitLink> links;
  for (const RevisitPair& p : pairs) links.push_back({p.i, p.j, truth[p.i].conjugate() * truth[p.j], 0.001});
  return links;
}

TEST(RevisitCandidates, AnOrbitRevisitsItsStartAfterTheTurn) {
  const auto q = Orbit(120, 3.6);  // 428 degrees: views 100-119 see what 0-19 saw
  const auto pairs = RevisitCandidates(q, 20, 40, 2);
  ASSERT_FALSE(pairs.empty());
  for (const RevisitPair& p : pairs) {
    EXPECT_LT(p.axis_angle_deg, 20);
    EXPECT_GE(p.j - p.i, 80);  // only after the camera left: 40 degrees out and back
  }
}

TEST(RevisitCandidates, NoneWhereTheCameraNeverComesBack) {
  EXPECT_TRUE(RevisitCandidates(Orbit(50, 3.6), 20, 40, 2).empty());  // a 180 degree pan
  EXPECT_TRUE(RevisitCandidates(Orbit(300, 0), 20, 40, 2).empty());   // a static shot: never left
  EXPECT_TRUE(RevisitCandidates({}, 20, 40, 2).empty());
  EXPECT_TRUE(RevisitCandidates({Eigen::Quaterniond::Identity()}, 20, 40, 2).empty());
}

TEST(RevisitCandidates, APanThereAndBackRevisits) {
  std::vector<Eigen::Quaterniond> q;
  for (int k = 0; k <= 30; ++k) q.push_back(Yaw(2 * k));
  for (int k = 29; k >= 0; --k) q.push_back(Yaw(2 * k));
  const auto pairs = RevisitCandidates(q, 10, 40, 1);
  ASSERT_FALSE(pairs.empty());
  EXPECT_EQ(pairs.back().i, 0);  // the return to the start links to the start
  EXPECT_EQ(pairs.back().j, 60);
}

TEST(CloseRevisitLoops, TheLoopClosesOnADriftingOrbit) {
  const auto truth = Orbit(120, 3.6);
  const auto solved = Drifted(truth, 0.05);  // 6 degrees off by the end
  const double before = MeanErrorDeg(solved, truth);
  ASSERT_GT(before, 2);
  LoopClosureOptions o;
  o.step_sigma_rad = 0.05 * kDeg;
  const LoopClosure closed = CloseRevisitLoops(solved, TrueLinks(truth, RevisitCandidates(solved, 20, 40, 2)), o);
  EXPECT_TRUE(closed.changed);
  EXPECT_GT(closed.links_used, 10);
  EXPECT_EQ(closed.links_rejected, 0);
  EXPECT_LT(MeanErrorDeg(closed.world_from_cam, truth), 0.5 * before);
  EXPECT_EQ(closed.world_from_cam[0].coeffs(), solved[0].coeffs());  // the gauge holds
}

TEST(CloseRevisitLoops, NoLinksChangeNothing) {
  const auto solved = Drifted(Orbit(40, 3.6), 0.05);
  const LoopClosure closed = CloseRevisitLoops(solved, {}, {});
  EXPECT_FALSE(closed.changed);
  ASSERT_EQ(closed.world_from_cam.size(), solved.size());
  for (size_t k = 0; k < solved.size(); ++k) EXPECT_EQ(closed.world_from_cam[k].coeffs(), solved[k].coeffs());
}

TEST(CloseRevisitLoops, AWrongLinkIsRejectedAndMalformedOnesIgnored) {
  const auto truth = Orbit(120, 3.6);
  const auto solved = Drifted(truth, 0.01);
  std::vector<RevisitLink> links{{5, 105, Yaw(90) * (truth[5].conjugate() * truth[105]), 0.001},
                                 {-1, 3, Eigen::Quaterniond::Identity(), 0.001},
                                 {2, 500, Eigen::Quaterniond::Identity(), 0.001},
                                 {4, 4, Eigen::Quaterniond::Identity(), 0.001},
                                 {1, 101, Eigen::Quaterniond::Identity(), 0}};
  LoopClosureOptions o;
  o.step_sigma_rad = 0.01 * kDeg;
  const LoopClosure closed = CloseRevisitLoops(solved, links, o);
  EXPECT_FALSE(closed.changed);
  EXPECT_EQ(closed.links_used, 0);
  EXPECT_EQ(closed.links_rejected, 5);
}

TEST(CarryCentres, DisplacementsTurnWithTheirView) {
  const std::vector<Eigen::Quaterniond> before{Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()};
  const std::vector<Eigen::Quaterniond> after{Yaw(90), Yaw(90)};
  const auto c = CarryCentres(before, after, {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 4)});
  EXPECT_EQ(c[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR((c[1] - Eigen::Vector3d(2, 2, 3)).norm(), 0, 1e-12);  // +z turned 90 degrees about y: +x
  EXPECT_TRUE(CarryCentres({}, {}, {}).empty());
}

}  // namespace
}  // namespace hapcine
