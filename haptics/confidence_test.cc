#include "haptics/confidence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "haptics/haptic_models.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using testing::MakeEffectPath;
using testing::MaxCoord;

TEST(Confidence, GainCurveIsSmoothAndMonotone) {
  EXPECT_EQ(ConfidenceGain(0), 0);
  EXPECT_DOUBLE_EQ(ConfidenceGain(kLowMedianConfidence), 0.5);  // the doubtful median: half
  EXPECT_EQ(ConfidenceGain(kFullGainConfidence), 1);
  EXPECT_EQ(ConfidenceGain(1), 1);
  double prev = 0;
  for (double c = 0.001; c <= 1; c += 0.001) {
    const double g = ConfidenceGain(c);
    EXPECT_GE(g, prev);
    // C1: no step larger than the curve's peak slope (1.875 / 0.24) allows.
    EXPECT_LE(g - prev, 1.875 / kFullGainConfidence * 0.001 + 1e-12) << c;
    prev = g;
  }
  const double h = 1e-6;  // flat at both ends
  EXPECT_LT(ConfidenceGain(h) / h, 1e-6);
  EXPECT_LT((1 - ConfidenceGain(kFullGainConfidence - h)) / h, 1e-6);
}

CameraPath WithConfidence(CameraPath path, double (*confidence_at)(double)) {
  for (CameraFrame& f : path.frames) f.confidence = confidence_at(f.time_s);
  return path;
}

HapticTrack Cinematic(const CameraPath& path) {
  HapticOptions o;
  o.rate_hz = 100;
  return MakeHapticTrack(path, o);
}

double HeadX(const HapticTrack& t, double time_s) {
  return t.samples[static_cast<size_t>(std::lround(time_s * t.rate_hz))].pos_m[0].x();
}

// A traveling whose estimate is poor (confidence 0.03) from 2 to 4 s: hardly
// felt there, and the rest of the shot still fills the range (the scaling
// ignores the span).
TEST(Confidence, LowConfidenceSpanIsFeltWeaklyAndIgnoredByScaling) {
  const CameraPath plain = MakeEffectPath(CameraEffect::kTraveling);  // moves 1 -> 6 s
  const CameraPath poor =
      WithConfidence(plain, [](double t) { return t > 2 && t < 4 ? 0.03 : 0.8; });
  const HapticTrack a = Cinematic(plain), b = Cinematic(poor);
  const double plain_change = std::abs(HeadX(a, 3.7) - HeadX(a, 2.3));
  const double poor_change = std::abs(HeadX(b, 3.7) - HeadX(b, 2.3));
  EXPECT_LT(poor_change, 0.1 * plain_change);
  EXPECT_NEAR(MaxCoord(b), 0.045, 1e-6);
  EXPECT_EQ(b.metadata.at("clamped_samples"), "0");
  EXPECT_EQ(b.metadata.at("rate_limited_samples"), "0");
  EXPECT_EQ(b.metadata.at("low_quality_shots"), "0");  // median 0.8
}

// A whole shot at confidence 0.1: its peak is the curve's gain times the
// range, not the full range.
TEST(Confidence, LowConfidenceShotIsScaledDown) {
  const CameraPath poor =
      WithConfidence(MakeEffectPath(CameraEffect::kTraveling), [](double) { return 0.1; });
  const HapticTrack t = Cinematic(poor);
  EXPECT_NEAR(MaxCoord(t), ConfidenceGain(0.1) * 0.045, 2e-4);
  EXPECT_EQ(t.metadata.at("low_quality_shots"), "1");
  // The path holds its confidence at single precision (0.1f).
  EXPECT_NEAR(std::stod(t.metadata.at("confidence_gain")), ConfidenceGain(0.1f), 1e-12);
}

// Confidence alternating 0.02 / 0.9 frame by frame: the window average
// keeps the gain steady; nothing jumps, nothing is NaN.
TEST(Confidence, NoisyConfidenceDoesNotPumpTheGain) {
  const CameraPath noisy = WithConfidence(MakeEffectPath(CameraEffect::kDutchAngle), [](double t) {
    return static_cast<int>(std::lround(t * 24)) % 2 ? 0.02 : 0.9;
  });
  const CameraPath& p = noisy;
  const std::vector<double> g = FrameConfidenceGains(p, SplitShots(p)[0]);
  for (size_t i = 13; i + 13 < g.size(); ++i) EXPECT_NEAR(g[i], g[i - 1], 0.05) << i;
  const HapticTrack t = Cinematic(noisy);
  for (const HapticSample& s : t.samples)
    for (const auto& v : s.pos_m) ASSERT_TRUE(v.allFinite());
  EXPECT_EQ(t.metadata.at("rate_limited_samples"), "0");
}

// A shot the estimator flagged doubtful (here by its border support: every
// frame confident) is felt at most at the doubtful median's gain, 1/2: its
// scaling and its reported gain; the other shot keeps its own.
TEST(Confidence, DoubtfulShotIsFeltAtMostAtHalfGain) {
  CameraPath p = MakeEffectPath(CameraEffect::kTraveling);
  for (CameraFrame& f : p.frames) f.shot = f.time_s < 3.5 ? 0 : 1;
  for (CameraFrame& f : p.frames) f.confidence = 0.9;
  const HapticTrack before = Cinematic(p);
  p.metadata["shot_quality.1"] =
      "first:105 last:209 frames:105 lost:0 median_confidence:0.9 border_support:0.25 doubtful:1";
  const auto q = AssessShotConfidence(p, SplitShots(p));
  EXPECT_EQ(q[0].gain, 1);
  EXPECT_DOUBLE_EQ(q[1].gain, 0.5);
  const HapticTrack after = Cinematic(p);
  EXPECT_EQ(after.metadata.at("confidence_gain"), "1;0.5");
  // Shot 1 moves half as far from where it starts; shot 0 is unchanged.
  double reach_before = 0, reach_after = 0, shot0_diff = 0;
  for (size_t i = 0; i < before.samples.size(); ++i) {
    const auto& b = before.samples[i].pos_m[0];
    const auto& a = after.samples[i].pos_m[0];
    if (before.samples[i].time_s < 3.4) shot0_diff = std::max(shot0_diff, (a - b).norm());
    if (before.samples[i].time_s > 4.5) {  // after the cut's crossfade
      reach_before = std::max(reach_before, b.norm());
      reach_after = std::max(reach_after, a.norm());
    }
  }
  EXPECT_LT(shot0_diff, 1e-12);
  ASSERT_GT(reach_before, 1e-3);
  EXPECT_NEAR(reach_after / reach_before, 0.5, 0.1);
  // Already below half: the flag takes nothing more away.
  EXPECT_DOUBLE_EQ(ShotQualityGain({0.2, 0.3, 0.4}, true), 0.3);
  EXPECT_DOUBLE_EQ(ShotQualityGain({0.8, 0.9, 1.0}, false), 0.9);
}

TEST(Confidence, LowQualityShots) {
  CameraPath p = MakeEffectPath(CameraEffect::kTraveling);
  for (CameraFrame& f : p.frames) f.shot = f.time_s < 3.5 ? 0 : 1;
  for (CameraFrame& f : p.frames) f.confidence = 0.5;
  auto q = AssessShotConfidence(p, SplitShots(p));
  ASSERT_EQ(q.size(), 2u);
  EXPECT_FALSE(q[0].low);
  EXPECT_FALSE(q[1].low);
  p.metadata["shot_quality.1"] =
      "first:105 last:209 frames:105 lost:0 median_confidence:0.5 doubtful:1";
  q = AssessShotConfidence(p, SplitShots(p));
  EXPECT_FALSE(q[0].low);
  EXPECT_TRUE(q[1].low);
  EXPECT_TRUE(q[1].header_doubtful);
  // Only the flag's own value: not a longer number, not another name ending in it.
  p.metadata["shot_quality.1"] = "first:105 last:209 frames:105 lost:0 not_doubtful:1 doubtful:10";
  EXPECT_FALSE(AssessShotConfidence(p, SplitShots(p))[1].header_doubtful);
  p.metadata["shot_quality.1"] =
      "first:105 last:209 frames:105 lost:0 median_confidence:0.5 doubtful:1";
  // 5.7 % of shot 0 lost (6 frames of 105): low.
  for (int i = 40; i < 46; ++i) {
    p.frames[i].model = kLostModel;
    p.frames[i].confidence = 0.0;
  }
  q = AssessShotConfidence(p, SplitShots(p));
  EXPECT_TRUE(q[0].low);
  EXPECT_EQ(q[0].lost, 6u);
  EXPECT_EQ(LowQualityShotLine(q[0]),
            "shot 0 (0.00-3.47 s): low quality (median confidence 0.50, 6 of 105 frames lost): "
            "haptic gain 1.00");
  // Ground truth (no confidence column): never low, gain 1.
  const CameraPath gt = MakeEffectPath(CameraEffect::kZoomIn);
  const auto g = AssessShotConfidence(gt, SplitShots(gt));
  EXPECT_FALSE(g[0].low);
  EXPECT_EQ(g[0].gain, 1);
}

}  // namespace
}  // namespace hapcine
