#include "datasets/synth_clip.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "datasets/synth_test_util.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("hapcine_synth_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

SynthOptions Tiny() {
  SynthOptions o;
  o.width = 160;
  o.height = 90;
  o.duration_s = 7.0 / 12;  // 14 frames at 24 fps: 2 still, 10 moving, 2 still
  o.x264_preset = "ultrafast";
  return o;
}

TEST(SynthClip, WritesVideoAndMatchingGroundTruth) {
  const fs::path dir = TempDir("ok") / "nested";  // created on demand
  const SynthResult r = SynthClip("traveling", Tiny(), dir.string());
  EXPECT_EQ(r.frames, 14);
  ASSERT_TRUE(fs::exists(r.video_path));
  ASSERT_TRUE(fs::exists(r.camera_path));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
  // "1 s" is 2 frames here: frames 0-2 (t <= 1/12 s) and 12-13 (t >= 6/12 s)
  // are still and rendered once per run of identical poses.
  EXPECT_EQ(r.rendered_views, 1 + 9 + 1);

  const CameraPath gt = ReadCameraPathFile(r.camera_path);
  ASSERT_EQ(gt.frames.size(), 14u);
  EXPECT_EQ(gt.width(), 160);
  EXPECT_EQ(gt.height(), 90);
  EXPECT_DOUBLE_EQ(gt.fps(), 24);
  EXPECT_EQ(gt.metadata.at("preset"), "traveling");
  const testing::DecodedVideo video = testing::DecodeVideo(r.video_path);
  int n = 0;
  for (const cv::Mat& img : video.frames) {
    EXPECT_EQ(img.cols, 160);
    EXPECT_EQ(img.rows, 90);
    EXPECT_NEAR(video.times_s[n], gt.frames[n].time_s, 1e-6);
    ++n;
  }
  EXPECT_EQ(n, 14);
  fs::remove_all(dir.parent_path());
}

TEST(SynthClip, FadeGoesBlackAndNoiseIsSeeded) {
  const fs::path dir = TempDir("fade");
  SynthOptions o = Tiny();
  o.duration_s = 7.0 / 8;  // 21 frames; black from frame 11 to 12 (3.5/8 .. 4/8 s)
  const SynthResult r = SynthClip("fade_to_black", o, dir.string());
  std::vector<double> mean;
  for (const cv::Mat& img : testing::DecodeVideo(r.video_path).frames) {
    mean.push_back(cv::mean(img)[1]);
  }
  ASSERT_EQ(mean.size(), 21u);
  EXPECT_GT(mean[0], 40);
  EXPECT_LT(mean[11], 20);  // black (plus codec ringing)
  EXPECT_GT(mean[20], 40);
  fs::remove_all(dir);
}

TEST(SynthClip, RenderIsDeterministicInTheSeed) {
  SynthOptions o = Tiny();
  const auto& p = synth::FindSynthPreset("arcing");
  const synth::ClipTiming timing{o.duration_s, o.fps};
  const auto view = SynthView(synth::PresetCameraAt(p, 0.3, timing, o.seed), 96, 54);
  synth::RenderOptions ro;
  const cv::Mat a = synth::RenderView(*SynthScene(1, synth::SceneStyle::kTextured), view, ro);
  const cv::Mat b = synth::RenderView(*synth::BuildHallScene(1, synth::SceneStyle::kTextured), view, ro);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  const cv::Mat c = synth::RenderView(*SynthScene(2, synth::SceneStyle::kTextured), view, ro);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1) / a.total(), 1.0);  // another seed, other textures
  // Rich texture: plenty of local contrast everywhere in the frame.
  cv::Mat gray;
  cv::cvtColor(a, gray, cv::COLOR_BGR2GRAY);
  cv::Scalar m, sd;
  cv::meanStdDev(gray, m, sd);
  EXPECT_GT(sd[0], 15);
}

TEST(SynthClip, HeadMoverChangesThePictureUnderAStaticCamera) {
  const fs::path dir = TempDir("head");
  const SynthResult r = SynthClip("head_turn", Tiny(), dir.string());
  const auto video = testing::DecodeVideo(r.video_path);
  ASSERT_EQ(video.frames.size(), 14u);
  // The camera never moves, but the head (in the middle of the frame) does.
  const cv::Rect middle(50, 20, 60, 50);
  const double change =
      cv::norm(video.frames[0](middle), video.frames[7](middle), cv::NORM_L1) / middle.area();
  EXPECT_GT(change, 5);
  EXPECT_EQ(r.rendered_views, 14);  // every frame rendered: the movers move
  fs::remove_all(dir);
}

TEST(SynthClip, VariantIsDeterministicAndDiffersFromTheOriginal) {
  SynthOptions o = Tiny();
  o.duration_s = 3 / 24.0;
  const fs::path dir = TempDir("variant");
  const SynthResult orig = SynthClip("dutch_angle", o, (dir / "orig").string());
  o.variant = "test";
  const SynthResult a = SynthClip("dutch_angle", o, (dir / "a").string());
  const SynthResult b = SynthClip("dutch_angle", o, (dir / "b").string());
  const auto va = testing::DecodeVideo(a.video_path), vb = testing::DecodeVideo(b.video_path);
  const auto vo = testing::DecodeVideo(orig.video_path);
  ASSERT_EQ(va.frames.size(), 3u);
  ASSERT_EQ(vo.frames.size(), 3u);
  for (size_t i = 0; i < va.frames.size(); ++i) {
    EXPECT_EQ(cv::norm(va.frames[i], vb.frames[i], cv::NORM_INF), 0) << i;
    EXPECT_GT(cv::norm(va.frames[i], vo.frames[i], cv::NORM_L1) / va.frames[i].total(), 10) << i;
  }
  fs::remove_all(dir);
}

// One factor of the variant's look can be left out (to measure it alone):
// without grain two renders of the variant differ only by the grain, and the
// header says what was left out. An unknown factor, or one without the
// variant, is a usage error.
TEST(SynthClip, VariantWithoutGrainDiffersOnlyByTheGrain) {
  SynthOptions o = Tiny();
  o.duration_s = 2 / 24.0;
  o.variant = "test";
  const fs::path dir = TempDir("variant_without");
  const SynthResult full = SynthClip("dutch_angle", o, (dir / "full").string());
  o.variant_without = {"grain"};
  const SynthResult clean = SynthClip("dutch_angle", o, (dir / "clean").string());
  const auto vf = testing::DecodeVideo(full.video_path), vc = testing::DecodeVideo(clean.video_path);
  ASSERT_EQ(vc.frames.size(), 2u);
  ASSERT_EQ(vf.frames.size(), 2u);
  cv::Mat diff;
  cv::absdiff(vf.frames[0], vc.frames[0], diff);
  const double mean_diff = cv::mean(diff)[0];
  EXPECT_GT(mean_diff, 1.0);  // grain sigma 3 (and its compression)
  EXPECT_LT(mean_diff, 6.0);  // the same scene, light and grade
  const CameraPath gt = ReadCameraPathFile(clean.camera_path);
  EXPECT_EQ(gt.metadata.at("grain_sigma"), "0");
  EXPECT_EQ(gt.metadata.at("variant_without"), "grain");
  o.variant_without = {"sharpness"};
  EXPECT_THROW(o.Check(), UsageError);
  o.variant_without = {"grain"};
  o.variant = "";
  EXPECT_THROW(o.Check(), UsageError);
  fs::remove_all(dir);
}

// A shutter opens and closes within one take: the motion-blurred variant's
// first frame after a hard cut shows the new shot only, not a blend of both
// (an edit joins whole frames).
TEST(SynthClip, BlurredFrameAfterACutShowsOnlyTheNewShot) {
  SynthOptions o = Tiny();
  o.variant = "test";  // every variant clip is motion-blurred
  const fs::path dir = TempDir("cut_blur");
  const SynthResult r = SynthClip("hard_cut", o, dir.string());
  const CameraPath gt = ReadCameraPathFile(r.camera_path);
  int cut = -1;
  for (size_t i = 1; i < gt.frames.size() && cut < 0; ++i)
    if (gt.frames[i].shot != gt.frames[i - 1].shot) cut = static_cast<int>(i);
  ASSERT_GT(cut, 0);
  ASSERT_LT(cut + 1, static_cast<int>(gt.frames.size()));
  const auto video = testing::DecodeVideo(r.video_path);
  const cv::Mat& before = video.frames[cut - 1];
  const cv::Mat& first = video.frames[cut];
  const cv::Mat& next = video.frames[cut + 1];
  // A blend of the two shots differs from the last frame of the old one by
  // about half as much as the new shot does.
  EXPECT_GT(cv::norm(first, before, cv::NORM_L1), 0.8 * cv::norm(next, before, cv::NORM_L1))
      << cv::norm(first, next, cv::NORM_L1);
  fs::remove_all(dir);
}

TEST(SynthClip, BadOutputDirLeavesNothingBehind) {
  const fs::path dir = TempDir("bad");
  fs::create_directories(dir);
  const fs::path file = dir / "a_file";
  std::ofstream(file) << "x";
  EXPECT_THROW(SynthClip("static_camera", Tiny(), file.string()), Error);
  EXPECT_THROW(SynthClip("static_camera", Tiny(), (file / "sub").string()), Error);
  if (::geteuid() != 0) {  // root ignores permissions
    const fs::path ro = dir / "readonly";
    fs::create_directories(ro);
    ::chmod(ro.c_str(), 0555);
    EXPECT_THROW(SynthClip("static_camera", Tiny(), ro.string()), Error);
    EXPECT_TRUE(fs::is_empty(ro));
    ::chmod(ro.c_str(), 0755);
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}),
            ::geteuid() != 0 ? 2 : 1);
  EXPECT_THROW(SynthClip("no_such_preset", Tiny(), dir.string()), UsageError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hapcine
