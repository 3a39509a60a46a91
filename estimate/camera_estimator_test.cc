#include "estimate/camera_estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/diagnostics.h"
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

TEST(DraftPreset, IsTheFastPresetWithTheDecoderSkipping) {
  EstimatorOptions fast, draft;
  ApplyFastPreset(&fast);
  ApplyDraftPreset(&draft);
  EXPECT_NO_THROW(draft.Check());
  EXPECT_EQ(draft.frames.max_working_side, fast.frames.max_working_side);
  EXPECT_EQ(draft.tracker.max_tracks, fast.tracker.max_tracks);
  EXPECT_TRUE(draft.frames.skip_nonref_frames);
  EXPECT_TRUE(draft.frames.skip_loop_filter);
  EXPECT_FALSE(fast.frames.skip_nonref_frames);
  draft.backend = "colmap";  // COLMAP reads every frame itself
  EXPECT_THROW(draft.Check(), UsageError);
}

// A slow pan over a noise texture, 320x180; throws a hapcine::Error instead
// of frame `fail_at` (if >= 0).
class PanSource : public FrameSource {
 public:
  PanSource(int count, int fail_at = -1, bool stills = false) : count_(count), fail_at_(fail_at) {
    info_.path = "pan";
    info_.stills = stills;
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

// PanSource's pan seen through a lens with radial distortion k1 (ffmpeg
// lenscorrection's convention, lens_distortion.h: the undistorted point is
// c + (p - c)(1 + k1 r^2), r in half-diagonals).
class DistortedPanSource : public FrameSource {
 public:
  DistortedPanSource(int count, double k1) : pan_(count) {
    const cv::Size size(pan_.info().width, pan_.info().height);
    map_x_.create(size, CV_32F);
    map_y_.create(size, CV_32F);
    const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
    const double half_diagonal = 0.5 * std::hypot(size.width, size.height);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const double r2 = (std::pow(x - cx, 2) + std::pow(y - cy, 2)) / std::pow(half_diagonal, 2);
        map_x_.at<float>(y, x) = static_cast<float>(cx + (x - cx) * (1 + k1 * r2));
        map_y_.at<float>(y, x) = static_cast<float>(cy + (y - cy) * (1 + k1 * r2));
      }
  }
  const VideoInfo& info() const override { return pan_.info(); }
  bool Next(Frame* frame) override {
    if (!pan_.Next(frame)) return false;
    for (cv::Mat* image : {&frame->gray, &frame->bgr}) {
      if (image->empty()) continue;
      cv::Mat seen;
      cv::remap(*image, seen, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_REFLECT);
      *image = seen;
    }
    return true;
  }

 private:
  PanSource pan_;
  cv::Mat map_x_, map_y_;
};

// The lens is measured at the defaults while the estimator runs on the
// frames as they are; where a k1 is kept the estimation starts again from
// the first frame with every track undistorted, which is the path a known
// k1 gives. A pinhole pan keeps none and its path is the one without the
// measurement.
TEST(EstimateCameraPath, ALensKeptStartsTheEstimationAgainUndistorted) {
  EstimatorOptions options;
  options.tracker.max_tracks = 200;
  DistortedPanSource distorted(96, 0.06);
  const CameraPath measured = EstimateCameraPath(distorted, options);
  ASSERT_TRUE(measured.metadata.count("k1"));
  const double k1 = std::stod(measured.metadata.at("k1"));
  EXPECT_NEAR(k1, 0.06, 0.03);
  EstimatorOptions known = options;
  known.lens_k1 = k1;
  DistortedPanSource again(96, 0.06);
  const CameraPath given = EstimateCameraPath(again, known);
  // The same up to the header's six digits of k1.
  ASSERT_EQ(measured.frames.size(), given.frames.size());
  for (size_t i = 0; i < given.frames.size(); ++i) {
    EXPECT_LT(measured.frames[i].world_from_cam.angularDistance(given.frames[i].world_from_cam),
              1e-6)
        << i;
    EXPECT_NEAR(measured.frames[i].focal_px.value() / given.frames[i].focal_px.value(), 1.0, 1e-5)
        << i;
  }

  PanSource pinhole(96);
  const CameraPath none = EstimateCameraPath(pinhole, options);
  EXPECT_FALSE(none.metadata.count("k1"));
  EstimatorOptions off = options;
  off.lens_distortion = false;
  PanSource pinhole_again(96);
  const CameraPath without = EstimateCameraPath(pinhole_again, off);
  ASSERT_EQ(none.frames.size(), without.frames.size());
  for (size_t i = 0; i < none.frames.size(); ++i)
    EXPECT_EQ(none.frames[i].world_from_cam.coeffs(), without.frames[i].world_from_cam.coeffs())
        << i;
}

TEST(EstimatorOptions, OneSourceOfLensDistortion) {
  // Two sources would undistort the tracks twice and write their sum as k1:
  // the pairs' measurement (on by default) gives way to a known k1 or the
  // bundle's, and those two exclude each other.
  EstimatorOptions o;
  EXPECT_TRUE(o.MeasuresLensFromPairs());
  o.lens_k1 = 0.02;
  EXPECT_NO_THROW(o.Check());
  EXPECT_FALSE(o.MeasuresLensFromPairs());
  o.lens_bundle = true;
  EXPECT_THROW(o.Check(), UsageError);
  o.lens_k1 = 0;
  EXPECT_NO_THROW(o.Check());
  EXPECT_FALSE(o.MeasuresLensFromPairs());
  o.lens_bundle = false;
  o.lens_distortion = false;
  EXPECT_FALSE(o.MeasuresLensFromPairs());
  o.lens_k1 = -0.01;
  EXPECT_NO_THROW(o.Check());
  o.lens_k1 = 0.6;
  EXPECT_THROW(o.Check(), UsageError);
}

TEST(EstimatorOptions, LensWindowsInRange) {
  EstimatorOptions o;
  o.lens_bundle_windows = 0;
  EXPECT_THROW(o.Check(), UsageError);
  o.lens_bundle_windows = 9;
  EXPECT_THROW(o.Check(), UsageError);
  o.lens_bundle_windows = 1;
  EXPECT_NO_THROW(o.Check());
}

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

// Still images (an image folder's VideoInfo::stills) are linked by
// descriptors and their path is not smoothed: the header says so, and the
// pan still comes out as a pan.
TEST(EstimateCameraPath, StillsAreNotSmoothed) {
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  PanSource video(12), stills(12, -1, true);
  const CameraPath smoothed = EstimateCameraPath(video, options);
  const CameraPath unsmoothed = EstimateCameraPath(stills, options);
  EXPECT_EQ(smoothed.metadata.at("smooth_sigma_frames"), "1.5");
  EXPECT_EQ(unsmoothed.metadata.at("smooth_sigma_frames"), "0");
  ASSERT_EQ(unsmoothed.frames.size(), 12u);
  EXPECT_EQ(unsmoothed.frames.back().shot, 0);
  EXPECT_GT(Eigen::AngleAxisd(unsmoothed.frames.back().world_from_cam.quaternion()).angle(), 0.0);
}

// PanSource as a decoder that skipped every other frame (--skip-nonref):
// it delivers frames 0, 2, 4, ... with the skipped ones' times attached, and
// `trailing` more skipped after the last.
class SkippingPanSource : public FrameSource {
 public:
  SkippingPanSource(int count, int trailing) : inner_(count), trailing_(trailing), count_(count) {}
  const VideoInfo& info() const override { return inner_.info(); }
  bool Next(Frame* frame) override {
    Frame f;
    if (!inner_.Next(&f)) return false;
    std::vector<double> skipped;
    if (f.index % 2 == 1) {  // drop it, keep its time for the next one
      skipped.push_back(f.time_s);
      if (!inner_.Next(&f)) return false;
    }
    *frame = f;
    frame->skipped_before_s = skipped;
    return true;
  }
  std::vector<double> SkippedAtEnd() const override {
    std::vector<double> t;
    for (int k = 0; k < trailing_; ++k) t.push_back((count_ + k) / 24.0);
    return t;
  }

 private:
  PanSource inner_;
  int trailing_, count_;
};

TEST(EstimateCameraPath, SkippedFramesGetTheirIndexTimeAndAPoseBetweenNeighbours) {
  SkippingPanSource source(31, 2);  // decodes 0, 2, ..., 30; then 31, 32 skipped
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  const CameraPath path = EstimateCameraPath(source, options);
  ASSERT_EQ(path.frames.size(), 33u);
  for (int i = 0; i < 33; ++i) {
    const CameraFrame& f = path.frames[i];
    EXPECT_EQ(f.frame, i);
    EXPECT_NEAR(f.time_s, i / 24.0, 1e-12) << i;  // MakeFrame's times
    if (i % 2 == 1 && i < 31) {  // halfway between its decoded neighbours
      const CameraFrame &a = path.frames[i - 1], &b = path.frames[i + 1];
      EXPECT_LT(f.world_from_cam.angularDistance(a.world_from_cam.slerp(0.5, b.world_from_cam)), 1e-9) << i;
      ASSERT_TRUE(f.confidence && b.confidence);
      EXPECT_LT(*f.confidence, *b.confidence + 1e-12) << i;
    }
  }
  // The two after the last decoded frame hold its pose.
  for (int i : {31, 32})
    EXPECT_LT(path.frames[i].world_from_cam.angularDistance(path.frames[30].world_from_cam), 1e-12);
  // The pan itself is there: the camera turned between frames 0 and 30.
  EXPECT_GT(path.frames[30].world_from_cam.angularDistance(path.frames[0].world_from_cam), 1e-3);
}

// The report's windows name the path's frames, not positions among the
// frames the decoder handed on (EstimatorRecords).
TEST(EstimateCameraPath, WindowRecordsNameTheFramesOfThePath) {
  SkippingPanSource source(31, 2);  // decodes 0, 2, ..., 30
  EstimatorOptions options;
  options.tracker.max_tracks = 150;
  JsonDiagnostics diagnostics({"window"});
  options.diagnostics = &diagnostics;
  EstimateCameraPath(source, options);
  const nlohmann::json windows = diagnostics.Document().at("windows");
  ASSERT_FALSE(windows.empty());
  int last = 0;
  for (const nlohmann::json& w : windows) {
    for (const nlohmann::json& k : w.at("keyframes")) EXPECT_EQ(k.at("frame").get<int>() % 2, 0) << k;
    last = std::max(last, w.at("last_frame").get<int>());
  }
  EXPECT_EQ(last, 30);  // position 15 before the mapping
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
