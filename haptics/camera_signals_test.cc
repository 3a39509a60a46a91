#include "haptics/camera_signals.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using testing::EffectPathSpec;
using testing::MakeEffectPath;

TEST(CameraSignals, DollyZoomSubjectDistanceFromTheMotionAlone) {
  // MakeEffectPath's dolly zoom keeps a subject 4 m away the same size.
  CameraPath p = MakeEffectPath(CameraEffect::kVertigo);
  p.metadata.clear();
  const auto d = DollyZoomSubjectDistance(p, SplitShots(p)[0]);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, testing::kSubjectDistanceM, 1e-6);  // from FOVs held as floats
  // In other units (an estimate in median-depth units), D follows them.
  for (auto& f : p.frames) f.center *= 0.25;
  EXPECT_NEAR(*DollyZoomSubjectDistance(p, SplitShots(p)[0]), 1.0, 1e-6);
  // Backward with a zoom-in is a dolly zoom too.
  const CameraPath back = MakeEffectPath(CameraEffect::kVertigo, -0.5);
  EXPECT_NEAR(*DollyZoomSubjectDistance(back, SplitShots(back)[0]), testing::kSubjectDistanceM,
              1e-6);
}

TEST(CameraSignals, NoDollyZoomWithoutBothMovementsInOppositeSenses) {
  for (CameraEffect e : {CameraEffect::kNone, CameraEffect::kZoomIn, CameraEffect::kTraveling,
                         CameraEffect::kDutchAngle}) {
    const CameraPath p = MakeEffectPath(e);
    EXPECT_FALSE(DollyZoomSubjectDistance(p, SplitShots(p)[0]).has_value()) << EffectName(e);
  }
  // Forward AND zoom-in (both magnify): not a dolly zoom (D would be < 0).
  CameraPath both = MakeEffectPath(CameraEffect::kZoomIn);
  for (size_t i = 0; i < both.frames.size(); ++i) both.frames[i].center.z() = -0.01 * i;
  EXPECT_FALSE(DollyZoomSubjectDistance(both, SplitShots(both)[0]).has_value());
  // A zoom-out with an unrelated forward move (zoom during the first half,
  // travel during the second): the fit does not explain the zoom.
  CameraPath apart = MakeEffectPath(CameraEffect::kZoomIn, -1.0);
  const size_t n = apart.frames.size();
  for (size_t i = 0; i < n; ++i) {
    apart.frames[i].center.z() = i > n / 2 ? -0.02 * (i - n / 2.0) : 0.0;
    if (i > n / 2) apart.frames[i].fov_deg = apart.frames[n / 2].fov_deg;
  }
  EXPECT_FALSE(DollyZoomSubjectDistance(apart, SplitShots(apart)[0]).has_value());
}

TEST(CameraSignals, DollyZoomFitToleratesEstimatorNoise) {
  EffectPathSpec s;
  s.effect = CameraEffect::kVertigo;
  s.noise = 0.002;  // 2 mm, 0.02 deg, 0.02 % FOV per frame
  const CameraPath p = MakeEffectPath(s);
  const auto d = DollyZoomSubjectDistance(p, SplitShots(p)[0]);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, testing::kSubjectDistanceM, 0.2);
}

TEST(CameraSignals, ShotReferenceDepthPrecedence) {
  const CameraPath p = MakeEffectPath(CameraEffect::kVertigo);  // metadata says 4 too
  const ShotRange shot = SplitShots(p)[0];
  EXPECT_EQ(ShotReferenceDepth(p, shot, 2.5), 2.5);  // explicit wins
  CameraPath q = p;
  q.metadata["subject_distance_m"] = "9";
  EXPECT_NEAR(ShotReferenceDepth(q, shot, 0), 4.0, 1e-6);  // the dolly zoom's own D
  const CameraPath zoom = MakeEffectPath(CameraEffect::kZoomIn);
  EXPECT_EQ(ShotReferenceDepth(zoom, SplitShots(zoom)[0], 0), 4.0);  // metadata
  CameraPath bare = zoom;
  bare.metadata.clear();
  EXPECT_EQ(ShotReferenceDepth(bare, SplitShots(bare)[0], 0), 1.0);  // median-depth units
}

TEST(CameraSignals, ErrorsNameTheFileLine) {
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/camera_signals_test.camera.csv";
  CameraPath p = MakeEffectPath(CameraEffect::kTraveling);
  p.metadata["comment"] = "x";
  WriteCameraPathFile(p, file);
  const std::vector<int> lines = CsvDataRowLines(file);
  ASSERT_EQ(lines.size(), p.frames.size());
  EXPECT_EQ(lines[1], lines[0] + 1);
  p.frames[40].center.x() = 5e6;  // absurd
  try {
    ValidatePathForHaptics(p, file, 1.0, &lines);
    FAIL();
  } catch (const Error& e) {
    const std::string want = file + ":" + std::to_string(lines[40]) + ": frame 40";
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
  }
  std::remove(file.c_str());
  EXPECT_TRUE(CsvDataRowLines(file).empty());
}

// 48 frames at 24 fps in four shots of 12, each shot change a jump of `jump_s`.
CameraPath FourShotsWithJumps(double jump_s) {
  EffectPathSpec spec;
  spec.effect = CameraEffect::kTraveling;
  spec.fps = 24;
  spec.still_s = 0.5;
  spec.motion_s = 1.0;
  CameraPath p = MakeEffectPath(spec);
  p.frames.resize(48);
  for (size_t i = 0; i < p.frames.size(); ++i) {
    p.frames[i].shot = static_cast<int>(i / 12);
    p.frames[i].time_s += jump_s * static_cast<double>(i / 12);
  }
  return p;
}

// A jump in time at a shot change would make the track span it: 1e7 s are
// 1e10 samples at 1 kHz. What shot changes skip is bounded by the 2 s the
// 48 frames cover; the first change past it is named.
TEST(CameraSignals, TimeJumpAtAShotChangeIsBoundedByThePathsOwnLength) {
  for (const double jump : {1000.0, 1e7, 2.5}) {
    try {
      ValidatePathForHaptics(FourShotsWithJumps(jump), "jump.camera.csv", 1.0);
      FAIL() << jump;
    } catch (const Error& e) {
      const std::string what = e.what();
      const std::string row = jump > 2 && jump < 3 ? "frame 24 (data row 25)" : "frame 12 (data row 13)";
      EXPECT_NE(what.find("jump.camera.csv: " + row), std::string::npos) << what;
      EXPECT_NE(what.find("at the change to shot"), std::string::npos) << what;
    }
  }
  // Gaps of --max-gap or less are missing frames, as inside a shot; what
  // goes beyond may add up to the frames' own 2 s.
  EXPECT_NO_THROW(ValidatePathForHaptics(FourShotsWithJumps(1.0), "ok.camera.csv", 1.0));
  EXPECT_NO_THROW(ValidatePathForHaptics(FourShotsWithJumps(1.6), "ok.camera.csv", 1.0));
  // A path of one-frame shots has no frame interval: only --max-gap holds.
  CameraPath single = FourShotsWithJumps(0.5);
  for (size_t i = 0; i < single.frames.size(); ++i) single.frames[i].shot = static_cast<int>(i);
  EXPECT_NO_THROW(ValidatePathForHaptics(single, "ok.camera.csv", 1.0));
  single.frames[47].time_s += 1.0;
  EXPECT_THROW(ValidatePathForHaptics(single, "bad.camera.csv", 1.0), Error);
}

}  // namespace
}  // namespace hapcine

namespace hapcine {
namespace {

TEST(CameraSignals, JoinAcrossLostFramesClosesTheGapRigidly) {
  CameraPath path;
  for (int i = 0; i < 6; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i * 0.04;
    f.shot = 0;
    const bool lost = i == 2 || i == 3;
    const int placed = lost ? 1 : i;
    f.world_from_cam = QuaternionFromPanTiltRoll(PanTiltRoll{10.0 * placed, 0, 0});
    f.center = Eigen::Vector3d(placed, 0, 0);
    f.fov_deg = 50 - placed;
    f.model = lost ? kLostModel : "general";
    path.frames.push_back(f);
  }
  const std::optional<CameraPath> joined = JoinAcrossLostFrames(path);
  ASSERT_TRUE(joined);
  const auto& j = joined->frames;
  // Frame 4 lands on the placeholder; frame 5 keeps its motion relative to 4.
  EXPECT_LT(AngleBetweenDeg(j[4].world_from_cam, j[3].world_from_cam), 1e-9);
  EXPECT_LT((j[4].center - j[3].center).norm(), 1e-12);
  EXPECT_FLOAT_EQ(j[4].fov_deg, j[3].fov_deg);  // held as a float
  EXPECT_NEAR(AngleBetweenDeg(j[5].world_from_cam, j[4].world_from_cam), 10, 1e-9);
  EXPECT_NEAR((j[5].center - j[4].center).norm(), 1, 1e-12);
  EXPECT_NEAR(j[5].fov_deg, 47.95, 0.01);  // 45 deg scaled by tan(49/2) / tan(46/2), not 49 - 1
  EXPECT_EQ(j[1].center, path.frames[1].center);  // before the gap: unchanged
  EXPECT_FALSE(JoinAcrossLostFrames(*joined));  // nothing left to close: no copy
  CameraPath none = path;
  for (auto& f : none.frames) f.model = "general";
  EXPECT_FALSE(JoinAcrossLostFrames(none));
}

TEST(CameraSignals, FadeToRestOverLostFrames) {
  const std::vector<double> t = {0, 1, 2, 3, 4, 5, 6};
  const std::vector<bool> lost = {false, false, true, true, true, false, false};
  std::vector<double> x = {0, 2, 2, 2, 2, 2, 3};  // held over the lost run, then +1
  FadeToRestOverLostFrames(t, lost, 2.0, &x);
  EXPECT_EQ(x[1], 2);
  EXPECT_NEAR(x[2], 1, 1e-12);  // halfway through the smooth step
  EXPECT_NEAR(x[3], 0, 1e-12);  // at rest
  EXPECT_NEAR(x[5], 0, 1e-12);
  EXPECT_NEAR(x[6], 1, 1e-12);  // the motion after resumes from rest
  std::vector<double> y = {0, 2, 2, 3};
  FadeToRestOverLostFrames({0, 1, 2, 3}, {false, false, true, false}, 0, &y);
  EXPECT_EQ(y[2], 0);
  EXPECT_EQ(y[3], 1);
}

}  // namespace
}  // namespace hapcine
