#include "estimate/camera_estimator.h"

#include <gtest/gtest.h>

namespace hapcine {
namespace {

TEST(FastPreset, IsValidAndCheaperThanTheDefaults) {
  const EstimatorOptions defaults;
  EstimatorOptions fast;
  ApplyFastPreset(&fast);
  EXPECT_NO_THROW(fast.Check());
  EXPECT_LT(fast.frames.max_working_side, defaults.frames.max_working_side);
  EXPECT_LT(fast.tracker.max_tracks, defaults.tracker.max_tracks);
  EXPECT_LE(fast.tracker.klt_window, defaults.tracker.klt_window);
  EXPECT_LE(fast.estimator.max_points, defaults.estimator.max_points);
  // What it does not touch stays as given.
  fast.estimator.prior_hfov_deg = 30;
  ApplyFastPreset(&fast);
  EXPECT_EQ(fast.estimator.prior_hfov_deg, 30);
}

TEST(FastPreset, SummaryNamesTheSettings) {
  EstimatorOptions fast;
  ApplyFastPreset(&fast);
  const std::string s = FastPresetSummary();
  EXPECT_NE(s.find("--max-side " + std::to_string(fast.frames.max_working_side)), std::string::npos) << s;
  EXPECT_NE(s.find("--tracks " + std::to_string(fast.tracker.max_tracks)), std::string::npos) << s;
}

}  // namespace
}  // namespace hapcine
