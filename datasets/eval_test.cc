#include "datasets/eval.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

constexpr double kWidth = 1920;

// A camera that pans, tilts, zooms in and dollies along a curve.
CameraPath MovingPath(int n, double fps = 24) {
  CameraPath p;
  p.metadata["width"] = "1920";
  p.metadata["fps"] = std::to_string(fps);
  for (int i = 0; i < n; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / fps;
    f.center = {0.5 * std::sin(0.05 * i), 0.02 * i, -0.03 * i};
    f.world_from_cam = QuaternionFromPanTiltRoll({0.8 * i, 5 * std::sin(0.1 * i), 0.2 * i});
    f.fov_deg = 60.0 - 0.1 * i;
    p.frames.push_back(f);
  }
  return p;
}

double FovFromFocalScale(double fov_deg, double scale) {
  return FovDegFromFocalPx(scale * FocalPxFromFovDeg(fov_deg, kWidth), kWidth);
}

void ExpectAllZero(const SegmentReport& s) {
  EXPECT_NEAR(s.rotation_deg.max, 0, 1e-6);
  EXPECT_NEAR(s.fov_deg.max, 0, 1e-9);
  EXPECT_NEAR(s.zoom_ratio_percent.max, 0, 1e-9);
  EXPECT_NEAR(s.ate.max, 0, 1e-9);
  EXPECT_NEAR(s.rpe_rotation_deg.max, 0, 1e-6);
  EXPECT_NEAR(s.rpe_translation.max, 0, 1e-9);
}

TEST(EvalTest, PathAgainstItselfIsZero) {
  const CameraPath gt = MovingPath(100);
  const EvalReport r = EvaluateCameraPaths(gt, gt, {});
  EXPECT_EQ(r.matched, 100);
  EXPECT_EQ(r.unmatched_gt, 0);
  EXPECT_EQ(r.unmatched_est, 0);
  EXPECT_EQ(r.matching_used, FrameMatching::kFrameIndex);
  ExpectAllZero(r.overall);
  ASSERT_TRUE(r.overall.ate_percent.has_value());
  EXPECT_NEAR(*r.overall.ate_percent, 0, 1e-9);
  EXPECT_NEAR(r.overall.align_scale, 1, 1e-9);
  EXPECT_EQ(r.overall.rpe_rotation_deg.count, 99);
  EXPECT_TRUE(r.shots.empty());
}

TEST(EvalTest, ConstantRotationOffsetAfterFirstFrame) {
  const CameraPath gt = MovingPath(50);
  CameraPath est = gt;
  const Eigen::Quaterniond offset(Eigen::AngleAxisd(DegToRad(2.0), Eigen::Vector3d(1, 1, 0).normalized()));
  for (size_t i = 1; i < est.frames.size(); ++i) {
    est.frames[i].world_from_cam = est.frames[i].world_from_cam * offset;
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  // Frame 0 has no error; the 49 others exactly 2 degrees.
  EXPECT_NEAR(r.overall.rotation_deg.mean, 2.0 * 49 / 50, 1e-9);
  EXPECT_NEAR(r.overall.rotation_deg.median, 2.0, 1e-9);
  EXPECT_NEAR(r.overall.rotation_deg.max, 2.0, 1e-9);
  EXPECT_NEAR(r.overall.rotation_deg.rmse, 2.0 * std::sqrt(49.0 / 50), 1e-9);
  EXPECT_NEAR(r.per_frame[10].rotation_deg, 2.0, 1e-9);
  // The step 0 -> 1 is off by the whole offset; later steps only by the
  // offset's conjugation of a ~1 degree step (O^-1 S O vs S): small.
  EXPECT_NEAR(r.per_frame[0].rpe_rotation_deg.value(), 2.0, 1e-9);
  EXPECT_LT(r.overall.rpe_rotation_deg.median, 0.1);
}

TEST(EvalTest, UniformFocalScaleGivesFovErrorButNoZoomRatioError) {
  const CameraPath gt = MovingPath(40);
  CameraPath est = gt;
  double expect_max = 0, expect_sum = 0, expect_pct_max = 0;
  for (auto& f : est.frames) {
    const double gt_fov = f.fov_deg;
    f.fov_deg = FovFromFocalScale(gt_fov, 1.1);  // held as a float: the error is of that float
    const double err = std::abs(f.fov_deg - gt_fov);
    expect_max = std::max(expect_max, err);
    expect_pct_max = std::max(expect_pct_max, 100 * err / gt_fov);
    expect_sum += err;
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_GT(r.overall.fov_deg.mean, 3.0);  // ~5 degrees at 60 degrees FOV
  EXPECT_NEAR(r.overall.fov_deg.mean, expect_sum / 40, 1e-9);
  EXPECT_NEAR(r.overall.fov_deg.max, expect_max, 1e-9);
  EXPECT_NEAR(r.overall.fov_percent.max, expect_pct_max, 1e-9);
  EXPECT_NEAR(r.overall.zoom_ratio_percent.max, 0, 1e-4);  // float FOVs: ratios within ~1e-7
}

TEST(EvalTest, ProgressiveFocalScaleGivesZoomRatioError) {
  const CameraPath gt = MovingPath(21);
  CameraPath est = gt;
  for (size_t i = 0; i < est.frames.size(); ++i) {
    est.frames[i].fov_deg = FovFromFocalScale(est.frames[i].fov_deg, 1.0 + 0.01 * i);
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  // Frame i's zoom ratio is off by i %: max 20 %, mean 10 %.
  // Within 1e-4 %: the FOVs are held as floats (~1e-7 of their value).
  EXPECT_NEAR(r.overall.zoom_ratio_percent.max, 20.0, 1e-4);
  EXPECT_NEAR(r.overall.zoom_ratio_percent.mean, 10.0, 1e-4);
  EXPECT_NEAR(r.per_frame[7].zoom_ratio_percent, 7.0, 1e-4);
}

TEST(EvalTest, FocalColumnIsUsedWhenPresent) {
  CameraPath gt = MovingPath(5);
  CameraPath est = gt;
  for (size_t i = 0; i < gt.frames.size(); ++i) {
    gt.frames[i].focal_px = 1000.0 * (1 + 0.1 * i);
    est.frames[i].focal_px = 500.0 * (1 + 0.1 * i);  // other resolution, same ratio
  }
  EXPECT_NEAR(EvaluateCameraPaths(gt, est, {}).overall.zoom_ratio_percent.max, 0, 1e-9);
}

CameraPath SimilarityTransformed(const CameraPath& gt, double s, const Eigen::Quaterniond& q,
                                 const Eigen::Vector3d& t) {
  CameraPath est = gt;
  for (auto& f : est.frames) {
    f.center = s * (q * f.center) + t;
    f.world_from_cam = q * f.world_from_cam;
  }
  return est;
}

TEST(EvalTest, SimilarityTransformedTrajectoryHasZeroError) {
  const CameraPath gt = MovingPath(80);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.0, Eigen::Vector3d(0.3, -1, 0.5).normalized()));
  const CameraPath est = SimilarityTransformed(gt, 0.37, q, {4, -2, 7});
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  ExpectAllZero(r.overall);
  EXPECT_NEAR(r.overall.align_scale, 1 / 0.37, 1e-9);

  // Without scale the ATE cannot be zero.
  EvalOptions se3;
  se3.align = TrajectoryAlignment::kSe3;
  EXPECT_GT(EvaluateCameraPaths(gt, est, se3).overall.ate.rmse, 0.01);
  // Rotation error does not depend on the world frame at all.
  EXPECT_NEAR(EvaluateCameraPaths(gt, est, se3).overall.rotation_deg.max, 0, 1e-6);
}

TEST(EvalTest, GaussianNoiseGivesAteOfSigmaRootThree) {
  const CameraPath gt = MovingPath(2000);
  CameraPath est = SimilarityTransformed(
      gt, 2.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY())), {1, 1, 1});
  std::mt19937 rng(42);
  const double sigma = 0.01;
  std::normal_distribution<double> noise(0.0, sigma * 2.0);  // est units are 2x GT
  for (auto& f : est.frames) f.center += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_NEAR(r.overall.ate.rmse, sigma * std::sqrt(3.0), 0.05 * sigma * std::sqrt(3.0));
  EXPECT_NEAR(*r.overall.ate_percent, 100 * r.overall.ate.rmse / r.overall.gt_path_length, 1e-9);
}

TEST(EvalTest, RotationOnlyClipReportsSpuriousTranslation) {
  CameraPath gt = MovingPath(30);
  for (auto& f : gt.frames) f.center.setZero();
  CameraPath est = gt;
  for (size_t i = 0; i < est.frames.size(); ++i) est.frames[i].center = {0.01 * i, 0, 0};
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_TRUE(r.overall.gt_static);
  EXPECT_FALSE(r.overall.ate_percent.has_value());
  EXPECT_NEAR(r.overall.est_path_length, 0.29, 1e-9);
  EXPECT_EQ(r.overall.gt_path_length, 0);
  EXPECT_TRUE(std::isfinite(r.overall.ate.rmse));
  const nlohmann::json j = EvalReportToJson(r);
  EXPECT_TRUE(j["overall"]["ate_percent"].is_null());
  EXPECT_NEAR(j["overall"]["spurious_translation"].get<double>(), 0.29, 1e-9);
  EXPECT_NE(FormatEvalTable(r).find("spurious translation"), std::string::npos);
  // An estimate that keeps the camera still is not flagged.
  const EvalReport same = EvaluateCameraPaths(gt, gt, {});
  EXPECT_EQ(FormatEvalTable(same).find("spurious"), std::string::npos);
}

TEST(EvalTest, ShotsAreAlignedSeparately) {
  // Two shots; the estimator restarts each at the origin with its own scale.
  CameraPath gt = MovingPath(40);
  for (size_t i = 0; i < gt.frames.size(); ++i) gt.frames[i].shot = i < 25 ? 0 : 1;
  CameraPath est = gt;
  const Eigen::Quaterniond gt0_inv = gt.frames[0].world_from_cam.conjugate();
  const Eigen::Quaterniond gt25_inv = gt.frames[25].world_from_cam.conjugate();
  for (size_t i = 0; i < est.frames.size(); ++i) {
    auto& f = est.frames[i];
    const bool first = i < 25;
    const Eigen::Quaterniond inv = first ? gt0_inv : gt25_inv;
    const Eigen::Vector3d c0 = gt.frames[first ? 0 : 25].center;
    const double scale = first ? 3.0 : 0.2;
    f.center = scale * (inv * (gt.frames[i].center - c0));
    f.world_from_cam = inv * gt.frames[i].world_from_cam;
    f.shot.reset();
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  ASSERT_EQ(r.shots.size(), 2u);
  EXPECT_EQ(r.shots[0].frames, 25);
  EXPECT_EQ(r.shots[1].frames, 15);
  EXPECT_NEAR(r.shots[0].align_scale, 1 / 3.0, 1e-9);
  EXPECT_NEAR(r.shots[1].align_scale, 1 / 0.2, 1e-9);
  ExpectAllZero(r.overall);
  EXPECT_EQ(r.overall.frames, 40);
  // RPE pairs never straddle the cut.
  EXPECT_EQ(r.overall.rpe_rotation_deg.count, 24 + 14);

  EvalOptions whole;
  whole.per_shot = false;
  EXPECT_GT(EvaluateCameraPaths(gt, est, whole).overall.rotation_deg.max, 1.0);
}

TEST(EvalTest, UnmatchedFramesAreCounted) {
  const CameraPath gt = MovingPath(30);
  CameraPath est = gt;
  est.frames.erase(est.frames.begin() + 20, est.frames.end());
  est.frames.erase(est.frames.begin() + 5);
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_EQ(r.matched, 19);
  EXPECT_EQ(r.unmatched_gt, 11);
  EXPECT_EQ(r.unmatched_est, 0);
  ExpectAllZero(r.overall);
}

// Lost frames hold a placeholder far from the truth: they are counted and
// left out of the errors, not scored as right or wrong.
TEST(EvalTest, LostFramesAreCountedAndExcluded) {
  const CameraPath gt = MovingPath(30);
  CameraPath est = gt;
  for (int i = 10; i < 16; ++i) {
    est.frames[i].world_from_cam = est.frames[9].world_from_cam;  // the placeholder
    est.frames[i].center = est.frames[9].center;
    est.frames[i].model = kLostModel;
    est.frames[i].confidence = 0;
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_EQ(r.matched, 30);
  EXPECT_EQ(r.overall.lost_frames, 6);
  EXPECT_EQ(r.overall.frames, 24);
  EXPECT_EQ(r.overall.rotation_deg.count, 24);
  ExpectAllZero(r.overall);  // the held placeholder would be degrees off
  const nlohmann::json j = EvalReportToJson(r);
  EXPECT_EQ(j["overall"]["lost_frames"], 6);
  EXPECT_NEAR(j["overall"]["lost_share"].get<double>(), 0.2, 1e-12);
  EXPECT_NE(FormatEvalTable(r).find("lost: 6 of 30 matched frames (20.0 %)"), std::string::npos);
  // Per shot: a shot lost entirely is listed with no frames compared.
  CameraPath gt2 = gt, est2 = est;
  for (int i = 0; i < 30; ++i) gt2.frames[i].shot = est2.frames[i].shot = i < 20 ? 0 : 1;
  for (int i = 20; i < 30; ++i) est2.frames[i].model = kLostModel;
  const EvalReport r2 = EvaluateCameraPaths(gt2, est2, {});
  ASSERT_EQ(r2.shots.size(), 2u);
  EXPECT_EQ(r2.shots[0].lost_frames, 6);
  EXPECT_EQ(r2.shots[1].lost_frames, 10);
  EXPECT_EQ(r2.shots[1].frames, 0);
  EXPECT_EQ(r2.overall.lost_frames, 16);
  EXPECT_EQ(r2.overall.frames, 14);
  // Every frame lost: nothing to compare, said as such.
  for (auto& f : est2.frames) f.model = kLostModel;
  EXPECT_THROW(EvaluateCameraPaths(gt2, est2, {}), Error);
}

TEST(EvalTest, FallsBackToTimeWhenIndicesDiffer) {
  const CameraPath gt = MovingPath(30);
  CameraPath est = gt;
  // Renumbered from 1000 (e.g. a trimmed export), times jittered < half a frame.
  for (size_t i = 0; i < est.frames.size(); ++i) {
    est.frames[i].frame = 1000 + static_cast<int>(i);
    est.frames[i].time_s += 0.01;
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_EQ(r.matching_used, FrameMatching::kTime);
  EXPECT_EQ(r.matched, 30);
  ExpectAllZero(r.overall);

  EvalOptions by_index;
  by_index.matching = FrameMatching::kFrameIndex;
  EXPECT_THROW(EvaluateCameraPaths(gt, est, by_index), Error);
}

// A 25 fps encode of 100 fps ground truth: index k is GT frame 4k. Auto must
// match by time, from the fps headers or, without them, from the drift.
TEST(EvalTest, MatchesByTimeWhenFrameRatesDiffer) {
  const CameraPath gt = MovingPath(100, 100);
  CameraPath est;
  est.metadata["fps"] = "25";
  for (size_t i = 0; i < gt.frames.size(); i += 4) {
    est.frames.push_back(gt.frames[i]);
    est.frames.back().frame = static_cast<int>(i / 4);
  }
  for (const bool headers : {true, false}) {
    CameraPath g = gt, e = est;
    if (!headers) {
      g.metadata.erase("fps");
      e.metadata.erase("fps");
    }
    const EvalReport r = EvaluateCameraPaths(g, e, {});
    EXPECT_EQ(r.matching_used, FrameMatching::kTime) << headers;
    EXPECT_EQ(r.matched, 25) << headers;
    ExpectAllZero(r.overall);
  }
}

// The same rate with all times shifted (an export that starts at 5 s): the
// index still names the same frame.
TEST(EvalTest, ConstantTimeOffsetKeepsIndexMatching) {
  const CameraPath gt = MovingPath(40);
  CameraPath est = gt;
  for (auto& f : est.frames) f.time_s += 5;
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  EXPECT_EQ(r.matching_used, FrameMatching::kFrameIndex);
  EXPECT_EQ(r.matched, 40);
  ExpectAllZero(r.overall);
}

TEST(EvalTest, ModelAgreement) {
  CameraPath gt = MovingPath(10);
  CameraPath est = gt;
  for (int i = 0; i < 10; ++i) {
    gt.frames[i].model = "rotation";
    est.frames[i].model = i < 7 ? "rotation" : "general";
  }
  const EvalReport r = EvaluateCameraPaths(gt, est, {});
  ASSERT_TRUE(r.overall.model_agreement.has_value());
  EXPECT_NEAR(*r.overall.model_agreement, 0.7, 1e-12);
  EXPECT_EQ(r.overall.model_frames, 10);
  EXPECT_FALSE(EvaluateCameraPaths(MovingPath(5), MovingPath(5), {}).overall.model_agreement);
}

TEST(EvalTest, ShotBoundaryPrecisionRecall) {
  CameraPath gt = MovingPath(40);
  CameraPath est = gt;
  for (auto& f : gt.frames) f.shot = f.frame >= 20;
  // The estimate finds the cut one frame late and splits again at 30.
  for (auto& f : est.frames) f.shot = (f.frame >= 21) + (f.frame >= 30);
  EvalOptions opt;
  opt.shot_tolerance_frames = 1;
  EvalReport r = EvaluateCameraPaths(gt, est, opt);
  ASSERT_TRUE(r.shot_boundaries.has_value());
  EXPECT_EQ(r.shot_boundaries->gt_boundaries, std::vector<int>({20}));
  EXPECT_EQ(r.shot_boundaries->est_boundaries, std::vector<int>({21, 30}));
  EXPECT_EQ(r.shot_boundaries->matched, 1);
  EXPECT_DOUBLE_EQ(*r.shot_boundaries->precision, 0.5);
  EXPECT_DOUBLE_EQ(*r.shot_boundaries->recall, 1);
  EXPECT_NE(FormatEvalTable(r).find("shot boundaries (+-1 frames): gt 1, estimate 2, matched 1: "
                                    "precision 0.5, recall 1"),
            std::string::npos)
      << FormatEvalTable(r);
  EXPECT_EQ(EvalReportToJson(r)["shot_boundaries"]["matched"], 1);
  opt.shot_tolerance_frames = 0;
  EXPECT_EQ(EvaluateCameraPaths(gt, est, opt).shot_boundaries->matched, 0);
  opt.shot_tolerance_frames = -1;
  EXPECT_THROW(opt.Check(), UsageError);
  // Only one path with a shot column: nothing to compare.
  r = EvaluateCameraPaths(gt, MovingPath(40), {});
  EXPECT_FALSE(r.shot_boundaries.has_value());
  EXPECT_TRUE(EvalReportToJson(r)["shot_boundaries"].is_null());
}

TEST(EvalTest, RpeDeltaAndTranslationScale) {
  const CameraPath gt = MovingPath(20);
  CameraPath est = gt;
  // Frame 10 displaced by 0.1 along x (GT units; same scale since only one
  // frame moves the Sim(3) fit stays close to identity).
  est.frames[10].center.x() += 0.1;
  EvalOptions opt;
  opt.rpe_delta = 3;
  opt.align = TrajectoryAlignment::kNone;
  const EvalReport r = EvaluateCameraPaths(gt, est, opt);
  EXPECT_EQ(r.overall.rpe_translation.count, 17);
  // Pairs (7,10) and (10,13) see the 0.1 displacement, the others none.
  EXPECT_NEAR(r.overall.rpe_translation.max, 0.1, 1e-9);
  EXPECT_NEAR(r.overall.rpe_translation.mean, 0.2 / 17, 1e-9);
  EXPECT_NEAR(r.overall.ate.max, 0.1, 1e-9);
}

TEST(EvalTest, SingleFrameAndDegenerateInputsStayFinite) {
  const CameraPath one = MovingPath(1);
  const EvalReport r = EvaluateCameraPaths(one, one, {});
  EXPECT_EQ(r.matched, 1);
  EXPECT_EQ(r.overall.rpe_rotation_deg.count, 0);
  EXPECT_TRUE(r.overall.gt_static);
  const nlohmann::json j = EvalReportToJson(r);
  EXPECT_TRUE(j["overall"]["rpe_rotation_deg"]["mean"].is_null());
  EXPECT_FALSE(j.dump().find("nan") != std::string::npos);

  // Estimate that never moves against a moving GT: scale 0, finite ATE.
  CameraPath still = MovingPath(10);
  for (auto& f : still.frames) f.center.setZero();
  const EvalReport r2 = EvaluateCameraPaths(MovingPath(10), still, {});
  EXPECT_TRUE(std::isfinite(r2.overall.ate.rmse));
  EXPECT_GT(r2.overall.ate.rmse, 0);
}

TEST(EvalTest, BadOptionsAreUsageErrors) {
  EvalOptions o;
  o.rpe_delta = 0;
  EXPECT_THROW(o.Check(), UsageError);
  EXPECT_THROW(ParseTrajectoryAlignment("sim4"), UsageError);
  EXPECT_EQ(ParseTrajectoryAlignment("se3"), TrajectoryAlignment::kSe3);
}

TEST(EvalTest, TableAndPerFrameFile) {
  const CameraPath gt = MovingPath(10);
  EvalReport r = EvaluateCameraPaths(gt, gt, {});
  const std::string table = FormatEvalTable(r);
  EXPECT_NE(table.find("rotation error (deg)"), std::string::npos);
  EXPECT_NE(table.find("matched 10"), std::string::npos);
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/eval_test_per_frame.csv";
  WritePerFrameErrorsFile(r, file);
  std::ifstream in(file);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 11);
  std::remove(file.c_str());
}

}  // namespace
}  // namespace hapcine
