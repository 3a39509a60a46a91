#include "datasets/eval_haptics.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/rotation.h"
#include "datasets/synth_clip.h"

namespace hapcine {
namespace {

// What a monocular estimator gives for a ground-truth path: its own world
// frame (first camera at the origin, looking down -Z) and its own scale.
CameraPath AsEstimate(const CameraPath& gt, double scale) {
  CameraPath est = gt;
  const Eigen::Matrix3d r0 = gt.frames[0].world_from_cam.toRotationMatrix();
  for (CameraFrame& f : est.frames) {
    f.center = scale * (r0.transpose() * (f.center - gt.frames[0].center));
    f.world_from_cam = Eigen::Quaterniond(r0.transpose() * f.world_from_cam.toRotationMatrix());
  }
  return est;
}

HapticEvalReport Compare(const CameraPath& gt, const CameraPath& est) {
  const EvalReport paths = EvaluateCameraPaths(gt, est, EvalOptions{});
  HapticOptions o;
  return EvaluateHapticDifference(gt, est, paths, o);
}

TEST(EvalHapticsTest, AnExactEstimateInAnotherFrameAndScaleFeelsTheSame) {
  for (const char* preset : {"traveling", "arcing", "hard_cut"}) {
    const CameraPath gt = SynthGroundTruth(preset, SynthOptions{});
    const HapticEvalReport r = Compare(gt, AsEstimate(gt, 0.17));
    EXPECT_EQ(r.model, "cinematic");
    EXPECT_GT(r.difference.num_samples, 600u);  // 7 s at the default 100 Hz
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_LT(r.difference.max_m[a], 1e-9) << preset << " " << a;
      // Every actuator moves (the arcing's left hand 8 mm with the default
      // washout, Equations 2-6: the high-pass had pushed it past 10 mm).
      EXPECT_GT(r.gt_peak_m[a], 0.005) << preset << " " << a;
    }
  }
}

TEST(EvalHapticsTest, ARollTooLargeShowsInTheHands) {
  const CameraPath gt = SynthGroundTruth("dutch_angle", SynthOptions{});
  CameraPath est = AsEstimate(gt, 1.0);
  for (CameraFrame& f : est.frames) {
    PanTiltRoll ptr = PanTiltRollFromQuaternion(f.world_from_cam);
    ptr.roll_deg *= 1.3;  // the estimate over-rotates by 30 %
    f.world_from_cam = QuaternionFromPanTiltRoll(ptr);
  }
  const HapticEvalReport r = Compare(gt, est);
  // Same scaling for both: the hands move 30 % further (of up to 45 mm).
  EXPECT_GT(r.difference.max_m[1], 0.005);
  EXPECT_LT(r.difference.max_m[1], 0.02);
  EXPECT_GT(r.difference.rms_m[2], 0.001);
  const nlohmann::json j = HapticEvalToJson(r);
  EXPECT_DOUBLE_EQ(j["actuators"]["left"]["max_m"].get<double>(), r.difference.max_m[1]);
  EXPECT_NE(FormatHapticEvalTable(r).find("left"), std::string::npos);
}

TEST(EvalHapticsTest, ScaleIsAppliedPerShot) {
  const CameraPath gt = SynthGroundTruth("hard_cut", SynthOptions{});
  CameraPath est = AsEstimate(gt, 1.0);
  // Shot 1 in another scale than shot 0 (the estimator restarts per shot).
  for (CameraFrame& f : est.frames) {
    if (*f.shot == 1) f.center *= 3.0;
  }
  const EvalReport paths = EvaluateCameraPaths(gt, est, EvalOptions{});
  const CameraPath scaled = ScaleEstimateToGroundTruth(est, paths);
  const Eigen::Vector3d d_gt = gt.frames.back().center - gt.frames[100].center;
  const Eigen::Vector3d d_est = scaled.frames.back().center - scaled.frames[100].center;
  EXPECT_NEAR(d_est.norm(), d_gt.norm(), 1e-6);
}

TEST(EvalHapticsTest, ErrorsNameThePathAtFault) {
  const CameraPath gt = SynthGroundTruth("traveling", SynthOptions{});
  CameraPath est = AsEstimate(gt, 1.0);
  for (size_t i = 60; i < est.frames.size(); ++i) est.frames[i].time_s += 3;  // a gap
  EvalOptions eo;
  eo.matching = FrameMatching::kFrameIndex;
  EvalReport paths = EvaluateCameraPaths(gt, est, eo);
  paths.gt_source = "gt.camera.csv";
  paths.est_source = "est.camera.csv";
  try {
    EvaluateHapticDifference(gt, est, paths, HapticOptions{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("est.camera.csv: frame 60"), std::string::npos)
        << e.what();
  }
}

// The estimate's time jumps by 1e7 s at its shot change: the comparison
// would build a 1 kHz track across it. Refused, naming the estimate's row.
TEST(EvalHapticsTest, TimeJumpAtAShotChangeIsAnError) {
  const CameraPath gt = SynthGroundTruth("hard_cut", SynthOptions{});
  CameraPath est = AsEstimate(gt, 1.0);
  size_t cut = 0;
  while (cut < est.frames.size() && *est.frames[cut].shot == *est.frames[0].shot) ++cut;
  ASSERT_LT(cut, est.frames.size());
  for (size_t i = cut; i < est.frames.size(); ++i) est.frames[i].time_s += 1e7;
  EvalOptions eo;
  eo.matching = FrameMatching::kFrameIndex;
  EvalReport paths = EvaluateCameraPaths(gt, est, eo);
  paths.gt_source = "gt.camera.csv";
  paths.est_source = "est.camera.csv";
  try {
    EvaluateHapticDifference(gt, est, paths, HapticOptions{});
    FAIL();
  } catch (const Error& e) {
    const std::string want = "est.camera.csv: frame " + std::to_string(est.frames[cut].frame);
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("shot change"), std::string::npos) << e.what();
  }
}

TEST(EvalHapticsTest, TracksThatDoNotOverlapAreAnError) {
  const CameraPath gt = SynthGroundTruth("traveling", SynthOptions{});
  CameraPath est = AsEstimate(gt, 1.0);
  for (CameraFrame& f : est.frames) f.time_s += 100;
  EvalOptions eo;
  eo.matching = FrameMatching::kFrameIndex;
  const EvalReport paths = EvaluateCameraPaths(gt, est, eo);
  EXPECT_THROW(EvaluateHapticDifference(gt, est, paths, HapticOptions{}), Error);
}

}  // namespace
}  // namespace hapcine
