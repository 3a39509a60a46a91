#include "datasets/movers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "datasets/render.h"
#include "datasets/synth_clip.h"
#include "datasets/synth_presets.h"

namespace hapcine::synth {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

CameraView PresetView(const std::string& name, double t, int w = 1280, int h = 720) {
  const ClipTiming timing;
  return SynthView(PresetCameraAt(FindSynthPreset(name), t, timing, 1), w, h);
}

// Vertical extent (pixels) of an ellipsoid's outline, sampled on its surface.
void ImageRows(const CameraView& v, const MoverEllipsoid& e, double* top, double* bottom) {
  for (int i = 0; i < 64; ++i) {
    for (int j = 1; j < 32; ++j) {
      const double a = 2 * M_PI * i / 64, b = M_PI * j / 32;
      const Vector3d local(std::sin(b) * std::cos(a), std::cos(b), std::sin(b) * std::sin(a));
      Vector2d xy;
      if (!ProjectToImage(v, e.center + e.world_from_local * local.cwiseProduct(e.radii), &xy)) {
        continue;
      }
      *top = std::min(*top, xy.y());
      *bottom = std::max(*bottom, xy.y());
    }
  }
}

TEST(Movers, HeadFillsHalfTheFrameHeightAndTurnsNodsAndBlinks) {
  const CameraView v = PresetView("head_turn", 3.0);
  for (double t : {0.0, 1.7, 3.5, 6.9}) {
    const MoverFrame f = MoversAt(MoverKind::kHead, t, 7, 1);
    double top = 1e9, bottom = -1e9;
    for (int part : {2, 3}) ImageRows(v, f.parts[part], &top, &bottom);  // face and hair
    const double fill = (bottom - top) / v.height;
    EXPECT_GT(fill, 0.4) << t;
    EXPECT_LT(fill, 0.7) << t;
  }
  // The head turns by tens of degrees, the eyes close at some instant.
  double max_turn = 0, min_eye = 1, max_eye = 0;
  const Eigen::Matrix3d r0 = MoversAt(MoverKind::kHead, 0, 7, 1).parts[2].world_from_local;
  for (int k = 0; k < 168; ++k) {
    const MoverFrame f = MoversAt(MoverKind::kHead, k / 24.0, 7, 1);
    const Eigen::AngleAxisd d(r0.transpose() * f.parts[2].world_from_local);
    max_turn = std::max(max_turn, d.angle() * 180 / M_PI);
    min_eye = std::min(min_eye, f.parts[5].radii.y());
    max_eye = std::max(max_eye, f.parts[5].radii.y());
  }
  EXPECT_GT(max_turn, 15);
  EXPECT_LT(min_eye, 0.3 * max_eye);
}

TEST(Movers, WalkersCrossTheViewDuringThePan) {
  // Every crossing walker is inside the picture at some frame, and moves.
  const MoverFrame first = MoversAt(MoverKind::kCrossing, 0, 7, 1);
  ASSERT_EQ(first.groups.size(), 3u);
  for (size_t g = 0; g < first.groups.size(); ++g) {
    bool seen = false;
    for (int k = 0; k < 168; ++k) {
      const CameraView v = PresetView("pan_crossing", k / 24.0);
      const MoverFrame f = MoversAt(MoverKind::kCrossing, k / 24.0, 7, 1);
      Vector2d xy;
      if (ProjectToImage(v, f.groups[g].center, &xy) && xy.x() > 0 && xy.x() < v.width) {
        seen = true;
      }
    }
    EXPECT_TRUE(seen) << g;
    const MoverFrame last = MoversAt(MoverKind::kCrossing, 7, 7, 1);
    EXPECT_GT((last.groups[g].center - first.groups[g].center).norm(), 5) << g;
  }
  EXPECT_EQ(MoversAt(MoverKind::kCrowd, 2, 7, 1).groups.size(), 14u);
  EXPECT_TRUE(MoversAt(MoverKind::kNone, 2, 7, 1).empty());
}

TEST(Movers, AreDeterministicInTheSeed) {
  const MoverFrame a = MoversAt(MoverKind::kCrowd, 2.5, 7, 1), b = MoversAt(MoverKind::kCrowd, 2.5, 7, 1);
  const MoverFrame c = MoversAt(MoverKind::kCrowd, 2.5, 7, 2);
  ASSERT_EQ(a.parts.size(), b.parts.size());
  double diff = 0;
  for (size_t i = 0; i < a.parts.size(); ++i) {
    EXPECT_EQ(a.parts[i].center, b.parts[i].center);
    diff += (a.parts[i].center - c.parts[i].center).norm();
  }
  EXPECT_GT(diff, 1);
}

// Mean absolute difference of neighbouring grey pixels (8-bit levels per pixel).
double MeanGradient(const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  const cv::Rect inner(0, 0, grey.cols - 1, grey.rows - 1);
  return 0.5 * (cv::mean(cv::abs(grey(inner + cv::Point(1, 0)) - grey(inner)))[0] +
                cv::mean(cv::abs(grey(inner + cv::Point(0, 1)) - grey(inner)))[0]);
}

TEST(Movers, DarkHallIsTheLowTextureHallAtAFifthOfTheAlbedo) {
  // head_turn_dark's background: the shading is linear in the albedo, so the dark hall is the
  // low-texture hall at a fifth of its brightness (the same lights and geometry; textures are
  // stored at 8 bits, hence the tolerance), dark but not black, and its picture changes by
  // under one grey level per pixel on average (mostly at object edges): little to track.
  EXPECT_EQ(FindSynthPreset("head_turn_dark").scene, SceneStyle::kDarkLowTexture);
  const CameraView v = PresetView("head_turn_dark", 0, 160, 90);
  RenderOptions o;
  o.threads = 2;
  const cv::Mat dark = RenderView(*SynthScene(5, SceneStyle::kDarkLowTexture, 2), v, o);
  const cv::Mat flat = RenderView(*SynthScene(5, SceneStyle::kLowTexture, 2), v, o);
  cv::Mat diff;
  cv::absdiff(5 * dark, flat, diff);
  EXPECT_LT(cv::mean(diff)[1], 0.02 * cv::mean(flat)[1]);
  EXPECT_NEAR(cv::mean(flat)[1] / cv::mean(dark)[1], 5, 0.1);
  EXPECT_GT(cv::mean(dark)[1], 5);
  EXPECT_LT(MeanGradient(dark), 1);  // 0.65 measured; the textured hall's is 10
  EXPECT_LT(MeanGradient(dark), 0.25 * MeanGradient(flat));
}

}  // namespace
}  // namespace hapcine::synth
