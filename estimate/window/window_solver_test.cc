#include "estimate/window/window_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/diagnostics.h"

namespace hapcine {
namespace {

constexpr double kPx = 1.0 / 960;  // one pixel at 960 px width, normalised units

WindowKeyframe Kf(int pos, MotionModel m, bool fixed = false, bool chain_start = false) {
  WindowKeyframe k;
  k.pos = pos;
  k.model = m;
  k.fixed = k.fixed_focal = fixed;
  k.chain_start = chain_start;
  return k;
}

// A synthetic window: keyframes every 4 frames with the given cameras
// (OpenCV axes), points in front of them, exact normalised observations;
// `offset_track`: that track is moved by `offset` in every keyframe after
// the first (a corner sliding along a silhouette).
struct SyntheticWindow {
  std::vector<KeyframeTracks> tracks;
  WindowInput input;
};

SyntheticWindow MakeWindow(const std::vector<BaCamera>& cams, const std::vector<MotionModel>& labels,
                           long offset_track = -1, Eigen::Vector2d offset = Eigen::Vector2d::Zero()) {
  SyntheticWindow w;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.4, 0.4), depth(2, 6);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 150; ++i) {
    const double z = depth(rng);
    points.emplace_back(u(rng) * z, 0.6 * u(rng) * z, z);
  }
  const int n = static_cast<int>(cams.size());
  w.tracks.resize(n);
  for (int k = 0; k < n; ++k)
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p = cams[k].world_from_cam.conjugate() * (points[i] - cams[k].center);
      if (p.z() <= 0.1) continue;
      Eigen::Vector2d x = std::exp(cams[k].log_focal) * p.head<2>() / p.z();
      if (static_cast<long>(i) == offset_track && k > 0) x += offset * k;
      w.tracks[k][static_cast<long>(i)] = x;
    }
  for (int k = 0; k < n; ++k) {
    WindowKeyframe kf = Kf(4 * k, labels[k], k == 0, k == 0);
    kf.cam = k == 0 ? cams[0] : cams[k - 1];  // the two-view start: the previous pose
    kf.cam.log_focal = cams[0].log_focal;
    kf.tracks = &w.tracks[k];
    w.input.keyframes.push_back(kf);
  }
  w.input.keyframes[0].cam = cams[0];
  for (int pos = 0; pos <= 4 * (n - 1); ++pos) w.input.frames.push_back(&w.tracks[pos / 4]);
  w.input.width = 960;
  w.input.height = 540;
  w.input.prior_log_focal = cams[0].log_focal;
  return w;
}

BaCamera Camera(double yaw_deg, Eigen::Vector3d center, double focal = 1.0) {
  BaCamera c;
  c.world_from_cam = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY()));
  c.center = center;
  c.log_focal = std::log(focal);
  return c;
}

TEST(PromoteShortRuns, AnIntervalBetweenTwoMoreGeneralNeighboursTakesTheirModel) {
  using M = MotionModel;
  const std::vector<WindowKeyframe> kf{Kf(0, M::kStatic, true, true), Kf(1, M::kGeneral), Kf(2, M::kRotation),
                                       Kf(3, M::kGeneral)};
  EXPECT_EQ(PromoteShortRuns(kf), (std::vector<M>{M::kStatic, M::kGeneral, M::kGeneral, M::kGeneral}));
}

TEST(PromoteShortRuns, RunsOfTwoArePromotedLongerRunsAndLessGeneralNeighboursAreNot) {
  using M = MotionModel;
  std::vector<WindowKeyframe> two{Kf(0, M::kStatic, true, true), Kf(1, M::kGeneral), Kf(2, M::kRotation),
                                  Kf(3, M::kRotation), Kf(4, M::kGeneral)};
  EXPECT_EQ(PromoteShortRuns(two)[2], M::kGeneral);
  EXPECT_EQ(PromoteShortRuns(two)[3], M::kGeneral);
  std::vector<WindowKeyframe> three = two;
  three.insert(three.begin() + 3, Kf(3, M::kRotation));
  EXPECT_EQ(PromoteShortRuns(three)[2], M::kRotation);
  // A rotation between two zooms: the zoom is not more general.
  const std::vector<WindowKeyframe> zoom{Kf(0, M::kStatic, true, true), Kf(1, M::kZoom), Kf(2, M::kRotation),
                                         Kf(3, M::kZoom)};
  EXPECT_EQ(PromoteShortRuns(zoom)[2], M::kRotation);
}

TEST(PromoteShortRuns, NeitherHeldKeyframesNorAChainStartsNeighbourChange) {
  using M = MotionModel;
  // The chain start has no interval of its own: it is no neighbour.
  const std::vector<WindowKeyframe> start{Kf(0, M::kGeneral, true, true), Kf(1, M::kRotation), Kf(2, M::kGeneral)};
  EXPECT_EQ(PromoteShortRuns(start)[1], M::kRotation);
  const std::vector<WindowKeyframe> held{Kf(0, M::kGeneral, true), Kf(1, M::kRotation, true), Kf(2, M::kGeneral)};
  EXPECT_EQ(PromoteShortRuns(held)[1], M::kRotation);
  EXPECT_TRUE(PromoteShortRuns({}).empty());
}

TEST(InitialFocalShift, StartsTheShotsFirstWindowAtTheMedianFocalSample) {
  WindowInput in;
  in.keyframes = {Kf(0, MotionModel::kStatic, true, true), Kf(4, MotionModel::kRotation)};
  in.keyframes[0].cam.log_focal = 0.1;
  in.focal_samples = {0.5, 0.2, 0.3};
  ASSERT_TRUE(InitialFocalShift(in, false).has_value());
  EXPECT_NEAR(*InitialFocalShift(in, false), 0.3 - 0.1, 1e-15);
  in.focal_observed = true;  // calibrated before: kept
  EXPECT_FALSE(InitialFocalShift(in, false).has_value());
  in.focal_observed = false;
  in.focal_samples.clear();  // nothing turned enough
  EXPECT_FALSE(InitialFocalShift(in, false).has_value());
}

TEST(InitialFocalShift, ALaterWindowOnlyWhenItRecalibratesTheLeadIn) {
  WindowInput in;
  in.keyframes = {Kf(40, MotionModel::kRotation, true), Kf(44, MotionModel::kRotation, true),
                  Kf(48, MotionModel::kRotation)};
  in.focal_samples = {0.4};
  EXPECT_FALSE(InitialFocalShift(in, false).has_value());
  EXPECT_TRUE(InitialFocalShift(in, true).has_value());
}

TEST(WindowCameras, EachIntervalSharesTheBlocksItsModelHasNot) {
  using M = MotionModel;
  std::vector<WindowKeyframe> kf{Kf(0, M::kStatic, true, true), Kf(1, M::kRotation), Kf(2, M::kZoom),
                                 Kf(3, M::kGeneral)};
  for (int i = 0; i < 4; ++i) kf[i].cam.log_focal = 0.1 * i;
  const std::vector<BaCamera> c = WindowCameras(kf, false, false);
  EXPECT_EQ(c[1].rotation_source, -1);
  EXPECT_EQ(c[1].center_source, 0);
  EXPECT_EQ(c[1].focal_source, 0);
  EXPECT_EQ(c[1].log_focal, c[0].log_focal);  // shared blocks start from the source's value
  EXPECT_EQ(c[2].rotation_source, 1);
  EXPECT_EQ(c[2].focal_source, -1);
  EXPECT_EQ(c[3].focal_source, 2);
  EXPECT_TRUE(c[0].fixed && c[0].fixed_focal);
  // Zoom in general intervals; labels instead of the keyframes' own; the lead-in's focal freed.
  EXPECT_EQ(WindowCameras(kf, true, false)[3].focal_source, -1);
  const std::vector<M> labels{M::kStatic, M::kStatic, M::kStatic, M::kStatic};
  EXPECT_EQ(WindowCameras(kf, false, false, &labels)[1].rotation_source, 0);
  EXPECT_FALSE(WindowCameras(kf, false, true)[0].fixed_focal);
}

TEST(FreedomTestLabels, FewTranslatingFramesAmongRotationAreTested) {
  using M = MotionModel;
  const std::vector<WindowKeyframe> few{Kf(0, M::kStatic, true, true), Kf(4, M::kRotation), Kf(8, M::kGeneral),
                                        Kf(12, M::kRotation)};
  const FreedomTestPlan plan = FreedomTestLabels(few);
  EXPECT_TRUE(plan.any);
  EXPECT_EQ(plan.drop_translation, (std::vector<char>{0, 0, 1, 0}));
  EXPECT_EQ(plan.labels[2], M::kRotation);
  // Half the frames translate: no test.
  const std::vector<WindowKeyframe> half{Kf(0, M::kStatic, true, true), Kf(4, M::kGeneral), Kf(8, M::kRotation)};
  EXPECT_FALSE(FreedomTestLabels(half).any);
  // Without translation, few zooming frames lose their zoom.
  const std::vector<WindowKeyframe> zoom{Kf(0, M::kStatic, true, true), Kf(4, M::kRotation),
                                         Kf(8, M::kRotationZoom), Kf(12, M::kRotation)};
  const FreedomTestPlan z = FreedomTestLabels(zoom);
  EXPECT_EQ(z.drop_zoom, (std::vector<char>{0, 0, 1, 0}));
  EXPECT_EQ(z.labels[2], M::kRotation);
}

TEST(PromotionLabels, FreeZoomIntervalsWithoutTranslationBecomeGeneral) {
  using M = MotionModel;
  const std::vector<WindowKeyframe> kf{Kf(0, M::kZoom, true, true), Kf(4, M::kZoom, true), Kf(8, M::kZoom),
                                       Kf(12, M::kRotationZoom), Kf(16, M::kGeneral), Kf(20, M::kRotation)};
  int promoted = 0;
  EXPECT_EQ(PromotionLabels(kf, &promoted),
            (std::vector<M>{M::kZoom, M::kZoom, M::kGeneral, M::kGeneral, M::kGeneral, M::kRotation}));
  EXPECT_EQ(promoted, 2);
}

TEST(DropBadTracks, ATrackNoRigidPointExplainsIsDroppedWhole) {
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(1, {0.1, 0, 0}), Camera(2, {0.2, 0, 0}),
                                    Camera(3, {0.3, 0, 0})};
  const long bad = 3;
  SyntheticWindow w = MakeWindow(truth, std::vector<MotionModel>(4, MotionModel::kGeneral), bad,
                                 Eigen::Vector2d(2 * kPx, -1.5 * kPx));
  std::vector<const KeyframeTracks*> at;
  for (const auto& t : w.tracks) at.push_back(&t);
  const WindowTracks wt = SelectWindowPoints(at, {}, 1000, 0);
  ASSERT_TRUE(wt.point_of_track.count(bad));
  std::vector<BaPoint> pts;
  std::vector<BaObservation> obs, kept;
  std::vector<BaCamera> cams = truth;
  cams[0].fixed = cams[1].fixed = true;
  InitWindowPoints(cams, wt, at, true, 0.2, &pts, &obs);
  BaOptions ba;
  ba.max_iterations = 20;
  BaSummary s = SolveBundle(&cams, &pts, obs, ba);
  ASSERT_TRUE(s.success);
  DropBadTracks(ba, 0.2, &cams, &pts, obs, &kept, &s);
  const int bad_point = wt.point_of_track.at(bad);
  int bad_left = 0, good_left = 0;
  for (const auto& o : kept) (o.point == bad_point ? bad_left : good_left) += 1;
  EXPECT_EQ(bad_left, 0);
  EXPECT_GT(good_left, static_cast<int>(0.9 * (obs.size() - 4)));
  // Nothing to drop: everything kept.
  SyntheticWindow clean = MakeWindow(truth, std::vector<MotionModel>(4, MotionModel::kGeneral));
  at.clear();
  for (const auto& t : clean.tracks) at.push_back(&t);
  const WindowTracks ct = SelectWindowPoints(at, {}, 1000, 0);
  cams = truth;
  cams[0].fixed = cams[1].fixed = true;
  InitWindowPoints(cams, ct, at, true, 0.2, &pts, &obs);
  s = SolveBundle(&cams, &pts, obs, ba);
  DropBadTracks(ba, 0.2, &cams, &pts, obs, &kept, &s);
  EXPECT_EQ(kept.size(), obs.size());
}

TEST(SolveWindow, ARotatingWindowKeepsItsLabelsAndRecoversThePoses) {
  using M = MotionModel;
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(2, {0, 0, 0}), Camera(4, {0, 0, 0}),
                                    Camera(6, {0, 0, 0})};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kRotation, M::kRotation, M::kRotation});
  JsonDiagnostics diagnostics;
  const WindowOutcome out = SolveWindow(w.input, WindowOptions{}, &diagnostics);
  ASSERT_TRUE(out.success);
  EXPECT_TRUE(out.revised_labels.empty());
  EXPECT_FALSE(out.translating);
  EXPECT_EQ(out.labels, (std::vector<M>{M::kStatic, M::kRotation, M::kRotation, M::kRotation}));
  EXPECT_LT(out.keyframe_cams[3].world_from_cam.angularDistance(truth[3].world_from_cam), 1e-4);
  EXPECT_LT(out.report.rms_px, 0.05);
  EXPECT_EQ(out.report.model, "constant_focal");
  EXPECT_TRUE(out.report.candidates.empty());  // no general interval, nothing tested
  EXPECT_FALSE(out.written_log_focal_shift.has_value());
  EXPECT_EQ(out.point_kept.size(), out.points.size());
}

// The focal profile (focal_profile.h) is a diagnostic: recorded when asked
// for, the outcome unchanged.
TEST(SolveWindow, TheFocalProfileIsRecordedOnRequestAndChangesNothing) {
  using M = MotionModel;
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(2, {0, 0, 0}), Camera(4, {0, 0, 0}),
                                    Camera(6, {0, 0, 0})};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kRotation, M::kRotation, M::kRotation});
  JsonDiagnostics wanted({"focal_profile", "focal_pull"});
  const WindowOutcome profiled = SolveWindow(w.input, WindowOptions{}, &wanted);
  const WindowOutcome plain = SolveWindow(w.input, WindowOptions{}, nullptr);
  ASSERT_TRUE(profiled.success);
  for (size_t i = 0; i < plain.keyframe_cams.size(); ++i) {
    EXPECT_EQ(profiled.keyframe_cams[i].log_focal, plain.keyframe_cams[i].log_focal);
    EXPECT_EQ(profiled.keyframe_cams[i].world_from_cam.coeffs(), plain.keyframe_cams[i].world_from_cam.coeffs());
  }
  const nlohmann::json doc = wanted.Document();
  ASSERT_EQ(doc["focal_profiles"].size(), 1u);
  const nlohmann::json& prof = doc["focal_profiles"][0];
  EXPECT_TRUE(prof["focal_observable"].get<bool>());
  // Exact tracks: the focal is pinned, at the solution.
  ASSERT_TRUE(prof["sigma_pct"].is_number());
  EXPECT_LT(prof["sigma_pct"].get<double>(), 0.01);
  EXPECT_NEAR(prof["minimum_pct"].get<double>(), 0, 0.05);
  ASSERT_EQ(doc["focal_pulls"].size(), 1u);
  EXPECT_GT(doc["focal_pulls"][0]["tracks"].size(), 100u);
  // Nothing asked, nothing recorded.
  JsonDiagnostics other({"window"});
  SolveWindow(w.input, WindowOptions{}, &other);
  EXPECT_FALSE(other.Document().contains("focal_profiles"));
}

// The drift fit is recorded on request and, without --drift-weights,
// changes nothing; with it, exact tracks show no growth: nothing is weighted.
TEST(SolveWindow, TheTrackDriftIsRecordedOnRequestAndExactTracksAreNotWeighted) {
  using M = MotionModel;
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(2, {0, 0, 0}), Camera(4, {0, 0, 0}),
                                    Camera(6, {0, 0, 0})};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kRotation, M::kRotation, M::kRotation});
  JsonDiagnostics wanted({"track_drift"});
  const WindowOutcome recorded = SolveWindow(w.input, WindowOptions{}, &wanted);
  const WindowOutcome plain = SolveWindow(w.input, WindowOptions{}, nullptr);
  WindowOptions weighting;
  weighting.drift_weights = true;
  const WindowOutcome weighted = SolveWindow(w.input, weighting, nullptr);
  ASSERT_TRUE(recorded.success);
  for (size_t i = 0; i < plain.keyframe_cams.size(); ++i) {
    EXPECT_EQ(recorded.keyframe_cams[i].log_focal, plain.keyframe_cams[i].log_focal);
    EXPECT_EQ(recorded.keyframe_cams[i].world_from_cam.coeffs(), plain.keyframe_cams[i].world_from_cam.coeffs());
    EXPECT_EQ(weighted.keyframe_cams[i].log_focal, plain.keyframe_cams[i].log_focal);
  }
  const nlohmann::json doc = wanted.Document();
  ASSERT_EQ(doc["track_drifts"].size(), 1u);
  EXPECT_FALSE(doc["track_drifts"][0]["weighted"].get<bool>());
  EXPECT_GT(doc["track_drifts"][0]["observations"].get<int>(), 100);
}

TEST(SolveWindow, ATranslationThePairsMisreadIsDroppedThroughRevisedLabels) {
  using M = MotionModel;
  // A pan; one interval among four labelled general: over the window one
  // depth per point does not buy anything, and the outcome asks for a
  // second solve without that translation (no recursion, no state).
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(2, {0, 0, 0}), Camera(4, {0, 0, 0}),
                                    Camera(6, {0, 0, 0}), Camera(8, {0, 0, 0})};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kRotation, M::kGeneral, M::kRotation, M::kRotation});
  const WindowOutcome first = SolveWindow(w.input, WindowOptions{}, nullptr);
  ASSERT_EQ(first.revised_labels.size(), 5u);
  EXPECT_EQ(first.revised_labels[2], M::kRotation);
  ASSERT_EQ(first.report.candidates.size(), 2u);
  EXPECT_EQ(first.report.candidates[1].name, "without");
  EXPECT_TRUE(first.report.candidates[1].chosen);
  EXPECT_LE(first.report.candidates[1].score, first.report.candidates[0].score);
  // The second solve, with the revised labels, is not tested again.
  for (int i = 0; i < 5; ++i) w.input.keyframes[i].model = first.revised_labels[i];
  w.input.labels_revised = true;
  const WindowOutcome second = SolveWindow(w.input, WindowOptions{}, nullptr);
  EXPECT_TRUE(second.revised_labels.empty());
  EXPECT_TRUE(second.success);
  EXPECT_TRUE(second.report.labels_revised);
  // Without the test the label stays.
  WindowOptions no_test;
  no_test.freedom_test = false;
  w.input.keyframes[2].model = M::kGeneral;
  w.input.labels_revised = false;
  EXPECT_TRUE(SolveWindow(w.input, no_test, nullptr).revised_labels.empty());
}

TEST(SolveWindow, AConstantFocalTravellingKeepsTheConstantFocalCandidate) {
  using M = MotionModel;
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}), Camera(1, {0.1, 0, 0}), Camera(2, {0.2, 0.02, 0}),
                                    Camera(3, {0.3, 0.04, 0}), Camera(4, {0.4, 0.06, 0})};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kGeneral, M::kGeneral, M::kGeneral, M::kGeneral});
  w.input.focal_observed = true;
  const WindowOutcome out = SolveWindow(w.input, WindowOptions{}, nullptr);
  ASSERT_TRUE(out.success);
  EXPECT_TRUE(out.translating);
  EXPECT_FALSE(out.report.zoom_by_bic);
  EXPECT_EQ(out.labels[4], M::kGeneral);
  int focal_candidates = 0;
  for (const auto& c : out.report.candidates)
    if (c.test == "focal") {
      ++focal_candidates;
      EXPECT_EQ(c.chosen, c.name == "constant_focal");
    }
  EXPECT_GE(focal_candidates, 2);
  EXPECT_GT(out.report.ba.iterations, 0);
  EXPECT_GT(out.report.ba.initial_cost, 0);
  EXPECT_LE(out.report.ba.final_cost, out.report.ba.initial_cost);
}

TEST(SolveWindow, ARecalibratedFocalReachesTheFramesAlreadyWritten) {
  using M = MotionModel;
  // A pan seen for the first time after frames that could not observe the
  // focal (the shot's first window was a dolly): the outcome carries the
  // focal change for the frames already written instead of rewriting them.
  const std::vector<BaCamera> truth{Camera(0, {0, 0, 0}, 1.2), Camera(5, {0, 0, 0}, 1.2),
                                    Camera(10, {0, 0, 0}, 1.2), Camera(15, {0, 0, 0}, 1.2)};
  SyntheticWindow w = MakeWindow(truth, {M::kStatic, M::kRotation, M::kRotation, M::kRotation});
  for (auto& k : w.input.keyframes) k.cam.log_focal = std::log(1.0);  // the prior
  w.input.keyframes[0].chain_start = false;
  w.input.keyframes[0].pos = 40;
  for (int i = 1; i < 4; ++i) w.input.keyframes[i].pos = 40 + 4 * i;
  w.input.frames_written = true;
  w.input.focal_samples = {std::log(1.2)};
  const WindowOutcome out = SolveWindow(w.input, WindowOptions{}, nullptr);
  ASSERT_TRUE(out.success);
  EXPECT_TRUE(out.focal_calibrated);
  ASSERT_TRUE(out.written_log_focal_shift.has_value());
  EXPECT_NEAR(*out.written_log_focal_shift, std::log(1.2), 0.01);
  EXPECT_NEAR(out.keyframe_cams[3].log_focal, std::log(1.2), 0.01);
}

}  // namespace
}  // namespace hapcine
