#include "estimate/geometry/motion_hypotheses.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <functional>
#include <random>

#include "core/error.h"

namespace hapcine {
namespace {

constexpr double kHalfHeight = 0.28125;  // 16:9
constexpr double kPx = 1.0 / 960;        // one pixel at 960 px width

struct Matches {
  std::vector<Eigen::Vector2d> u1, u2;
  std::vector<char> on_subject;
};

// Background matches over the whole frame moved by `background`, and a
// subject (an ellipse of semi-axes rx, ry about the centre: it covers that
// part of the frame) moved by `subject`; 0.3 px of noise.
Matches Scene(const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& background,
              const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& subject, double rx, double ry,
              unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-0.5, 0.5), y(-kHalfHeight, kHalfHeight);
  std::normal_distribution<double> noise(0, 0.3 * kPx);
  Matches m;
  for (int i = 0; i < 600; ++i) {
    const Eigen::Vector2d u(x(rng), y(rng));
    const bool on = std::pow(u.x() / rx, 2) + std::pow(u.y() / ry, 2) < 1;
    m.u1.push_back(u);
    m.u2.push_back((on ? subject(u) : background(u)) + Eigen::Vector2d(noise(rng), noise(rng)));
    m.on_subject.push_back(on);
  }
  return m;
}

Eigen::Vector2d Still(const Eigen::Vector2d& u) { return u; }
Eigen::Vector2d Slide(const Eigen::Vector2d& u) { return u + Eigen::Vector2d(12 * kPx, 5 * kPx); }
// A pan of 1 degree at focal 1 (50 degrees of view).
Eigen::Vector2d Pan(const Eigen::Vector2d& u) {
  const Eigen::Vector3d p = Eigen::AngleAxisd(0.01745, Eigen::Vector3d::UnitY()) * u.homogeneous();
  return p.hnormalized();
}

TEST(MotionHypotheses, BorderRadiusIsOneOnTheFrameEdge) {
  EXPECT_DOUBLE_EQ(BorderRadius({0, 0}, kHalfHeight), 0);
  EXPECT_DOUBLE_EQ(BorderRadius({0.5, 0}, kHalfHeight), 1);
  EXPECT_DOUBLE_EQ(BorderRadius({-0.1, -kHalfHeight}, kHalfHeight), 1);
  EXPECT_DOUBLE_EQ(BorderRadius({0.2, 0.5 * kHalfHeight}, kHalfHeight), 0.5);
}

TEST(MotionHypotheses, ResidualsOfTheModelThatMadeTheMatchesAreNoise) {
  const Matches m = Scene(Pan, Pan, 0.1, 0.1);
  const TwoViewResult r = SelectTwoViewModel(m.u1, m.u2, 1.0, TwoViewOptions{});
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.model, MotionModel::kRotation);
  const std::vector<double> sq = TwoViewResiduals(r, m.u1, m.u2);
  const std::vector<char> in = TwoViewInliers(r, sq, TwoViewThreshold(r, TwoViewOptions{}));
  EXPECT_GT(std::count(in.begin(), in.end(), 1), 590);
}

// A subject covering ~55 % of the frame slides over a still background:
// the majority (subject + background at infinity) reads as a sideways
// move; the border is still, and the camera is static.
TEST(MotionHypotheses, LargeSubjectOverAStillBackgroundLeavesTheCameraStatic) {
  const Matches m = Scene(Still, Slide, 0.42, 0.24);
  int subject = 0;
  for (char s : m.on_subject) subject += s;
  ASSERT_GT(subject, 250);
  MoverOptions off;
  off.enabled = false;
  const CameraMotion majority = SelectCameraMotion(m.u1, m.u2, 1.0, kHalfHeight, TwoViewOptions{}, off);
  EXPECT_EQ(majority.camera.model, MotionModel::kGeneral);  // what the border corrects
  const CameraMotion cm = SelectCameraMotion(m.u1, m.u2, 1.0, kHalfHeight, TwoViewOptions{}, MoverOptions{});
  EXPECT_TRUE(cm.border_motion);
  EXPECT_EQ(cm.camera.model, MotionModel::kStatic);
  int flagged = 0, wrong = 0;
  for (size_t i = 0; i < m.u1.size(); ++i) {
    flagged += m.on_subject[i] && !cm.camera.inliers[i];
    wrong += !m.on_subject[i] && !cm.camera.inliers[i];
  }
  EXPECT_GT(flagged, subject - 10);
  EXPECT_LT(wrong, 10);
  EXPECT_GT(cm.movers, subject - 10);
}

// The camera pans to follow a subject that fills most of the middle: the
// majority is still, the border turns. The camera is the border's.
TEST(MotionHypotheses, FollowedSubjectKeepsThePan) {
  const Matches m = Scene(Pan, Still, 0.42, 0.24);
  const CameraMotion cm = SelectCameraMotion(m.u1, m.u2, 1.0, kHalfHeight, TwoViewOptions{}, MoverOptions{});
  EXPECT_TRUE(cm.border_motion);
  EXPECT_EQ(cm.camera.model, MotionModel::kRotation);
}

// One rigid motion everywhere (a pan; a zoom, whose centre is still): the
// majority's result, unchanged.
TEST(MotionHypotheses, OneMotionIsTheMajoritysResult) {
  const auto zoom = [](const Eigen::Vector2d& u) -> Eigen::Vector2d { return 1.03 * u; };
  for (const auto& f : {std::function<Eigen::Vector2d(const Eigen::Vector2d&)>(Pan), std::function<Eigen::Vector2d(const Eigen::Vector2d&)>(zoom)}) {
    const Matches m = Scene(f, f, 0.3, 0.2);
    const TwoViewResult majority = SelectTwoViewModel(m.u1, m.u2, 1.0, TwoViewOptions{});
    const CameraMotion cm = SelectCameraMotion(m.u1, m.u2, 1.0, kHalfHeight, TwoViewOptions{}, MoverOptions{});
    EXPECT_FALSE(cm.border_motion);
    EXPECT_EQ(cm.camera.model, majority.model);
    EXPECT_EQ(cm.camera.inliers, majority.inliers);
  }
}

// Too few matches, or none on the border: the majority's result.
TEST(MotionHypotheses, DegenerateInputsGiveTheMajoritysResult) {
  const CameraMotion none = SelectCameraMotion({}, {}, 1.0, kHalfHeight, TwoViewOptions{}, MoverOptions{});
  EXPECT_FALSE(none.camera.valid);
  Matches m = Scene(Still, Slide, 0.42, 0.24);
  std::vector<Eigen::Vector2d> u1, u2;
  for (size_t i = 0; i < m.u1.size(); ++i)
    if (BorderRadius(m.u1[i], kHalfHeight) < 0.6) {
      u1.push_back(m.u1[i]);
      u2.push_back(m.u2[i]);
    }
  const CameraMotion inner = SelectCameraMotion(u1, u2, 1.0, kHalfHeight, TwoViewOptions{}, MoverOptions{});
  EXPECT_FALSE(inner.border_motion);
  EXPECT_EQ(inner.border_tracks, 0);
  MoverOptions bad;
  bad.border_radius = 1;
  EXPECT_THROW(bad.Check(), UsageError);
}

}  // namespace
}  // namespace hapcine
