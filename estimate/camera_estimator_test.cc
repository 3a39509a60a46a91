#include "estimate/camera_estimator.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>
#include <vector>

#include "core/error.h"
#include "extract/test_frames.h"

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
  EXPECT_LE(fast.estimator.spread_points_factor, defaults.estimator.spread_points_factor);
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

// A slow pan over a noise texture, 320x180; throws a hapcine::Error instead
// of frame `fail_at` (if >= 0).
class PanSource : public FrameSource {
 public:
  PanSource(int count, int fail_at = -1) : count_(count), fail_at_(fail_at) {
    info_.path = "pan";
    info_.width = 320;
    info_.height = 180;
    info_.fps = 24;
    info_.frame_count = count;
  }
  const VideoInfo& info() const override { return info_; }
  bool Next(Frame* frame) override {
    if (next_ == fail_at_) throw Error(info_.path, "decoder failed");
    if (next_ >= count_) return false;
    *frame = testing::MakeFrame(testing::Shifted(texture_, 2.0 * next_, 0, {320, 180}), next_);
    ++next_;
    return true;
  }

 private:
  VideoInfo info_;
  cv::Mat texture_ = testing::NoiseTexture({700, 400}, 7);
  int count_, fail_at_, next_ = 0;
};

TEST(EstimateCameraPath, EveryFrameInOrderWithProgressOnTheCallersThread) {
  PanSource source(30);
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  std::vector<long> done;
  const std::thread::id caller = std::this_thread::get_id();
  bool other_thread = false;
  const CameraPath path = EstimateCameraPath(source, options, [&](long d, long total) {
    done.push_back(d);
    EXPECT_EQ(total, 30);
    other_thread |= std::this_thread::get_id() != caller;
  });
  ASSERT_EQ(path.frames.size(), 30u);
  for (size_t i = 0; i < path.frames.size(); ++i) EXPECT_EQ(path.frames[i].frame, static_cast<int>(i));
  ASSERT_EQ(done.size(), 30u);
  EXPECT_EQ(done.back(), 30);
  EXPECT_FALSE(other_thread);
  // Same result as a second run (the pipeline adds no nondeterminism).
  PanSource again(30);
  const CameraPath path2 = EstimateCameraPath(again, options);
  ASSERT_EQ(path2.frames.size(), 30u);
  for (size_t i = 0; i < 30; ++i)
    {
    EXPECT_EQ(path.frames[i].center, path2.frames[i].center) << i;
    EXPECT_EQ(path.frames[i].world_from_cam.coeffs(), path2.frames[i].world_from_cam.coeffs()) << i;
  }
}

TEST(EstimateCameraPath, DecoderErrorReachesTheCaller) {
  PanSource source(40, 12);
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  try {
    EstimateCameraPath(source, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("decoder failed"), std::string::npos) << e.what();
  }
}

TEST(EstimateCameraPath, ProgressCallbackThrowingStopsTheTrackerThread) {
  PanSource source(200);
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  EXPECT_THROW(EstimateCameraPath(source, options,
                                  [](long done, long) {
                                    if (done == 3) throw std::runtime_error("stop");
                                  }),
               std::runtime_error);
}

}  // namespace
}  // namespace hapcine
