#include "extract/feature_tracker.h"

#include <gtest/gtest.h>

#include <functional>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/error.h"
#include "extract/shot_detector.h"
#include "extract/test_frames.h"

namespace hapcine {
namespace {

using testing::BlendedAcross;
using testing::MakeFrame;
using testing::NoiseTexture;
using testing::Shifted;

const cv::Size kDecoded(640, 480);

std::map<long, Eigen::Vector2d> ById(const FrameTracks& t) {
  std::map<long, Eigen::Vector2d> m;
  for (const auto& p : t.points) m[p.track_id] = p.px;
  return m;
}

TrackerOptions SmallOptions() {
  TrackerOptions o;
  o.max_tracks = 300;
  return o;
}

// Sub-pixel translations, tracked on a half-size working image, come back in
// decoded pixels to better than 0.1 px.
TEST(FeatureTrackerTest, TranslationIsTrackedToATenthOfAPixel) {
  // Exact rendering: warpAffine would add its own 1/32-px quantisation.
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  std::vector<cv::Point2d> shift;
  for (int i = 0; i < 10; ++i) {
    shift.emplace_back(1.37 * i, -0.61 * i);
    const cv::Mat texture_from_decoded =
        (cv::Mat_<double>(2, 3) << 1, 0, -shift[i].x, 0, 1, -shift[i].y);
    out.push_back(tracker.Process(
        MakeFrame(testing::AnalyticTexture(kDecoded, texture_from_decoded, 1), i, 0.5)));
  }
  EXPECT_EQ(out[0].boundary, ShotBoundary::kStart);
  EXPECT_GT(out[0].points.size(), 250u);
  const auto first = ById(out[0]);
  for (int i = 1; i < 10; ++i) {
    EXPECT_EQ(out[i].boundary, ShotBoundary::kNone);
    EXPECT_EQ(out[i].shot, 0);
    EXPECT_FALSE(out[i].blank);
    EXPECT_GT(out[i].quality, 0.8);
    int checked = 0, good = 0;
    double sum_err = 0;
    for (const auto& [id, px] : ById(out[i])) {
      auto it = first.find(id);
      if (it == first.end()) continue;
      const Eigen::Vector2d moved = px - it->second;
      const double err = (moved - Eigen::Vector2d(shift[i].x, shift[i].y)).norm();
      sum_err += err;
      ++checked;
      good += err < 0.1;
    }
    ASSERT_GT(checked, 200) << "frame " << i;
    EXPECT_LT(sum_err / checked, 0.075) << "frame " << i;
    EXPECT_GT(good, 0.9 * checked) << "frame " << i;
  }
}

// Drift: frame-to-frame KLT adds an independent error every frame (here
// the sensor noise of each frame), so a 100-frame track random-walks away
// from its point. Tracks anchored on the frame of their detection
// (klt_anchor_frames) stay within a bound of the truth however old: 0.23,
// -0.17 px a frame, noise sigma 8 grey levels a frame.
double MeanDriftAfter100Frames(int anchor_frames, size_t* checked) {
  TrackerOptions o = SmallOptions();
  o.klt_anchor_frames = anchor_frames;
  FeatureTracker tracker(o);
  std::map<long, Eigen::Vector2d> first;
  FrameTracks last;
  const int frames = 100;
  const cv::Mat texture = NoiseTexture({800, 600}, 3);
  cv::RNG rng(7);
  for (int i = 0; i < frames; ++i) {
    cv::Mat decoded = Shifted(texture, 0.23 * i, -0.17 * i, kDecoded), noisy, noise(kDecoded, CV_16SC3);
    rng.fill(noise, cv::RNG::NORMAL, 0, 8);
    decoded.convertTo(noisy, CV_16SC3);
    noisy += noise;
    noisy.convertTo(decoded, CV_8UC3);
    last = tracker.Process(MakeFrame(decoded, i, 0.5));
    if (i == 0) first = ById(last);
  }
  double sum = 0;
  *checked = 0;
  for (const auto& [id, px] : ById(last)) {
    const auto it = first.find(id);
    if (it == first.end()) continue;
    sum += (px - it->second - Eigen::Vector2d(0.23 * (frames - 1), -0.17 * (frames - 1))).norm();
    ++*checked;
  }
  return *checked ? sum / *checked : 1e9;
}

TEST(FeatureTrackerTest, AnchoredTracksDoNotDrift) {
  size_t plain_checked = 0, anchored_checked = 0;
  const double plain = MeanDriftAfter100Frames(0, &plain_checked);
  const double anchored = MeanDriftAfter100Frames(10, &anchored_checked);
  // Measured: 0.12 px plain, 0.053 anchored, no track lost to the bound.
  EXPECT_GT(plain_checked, 200u);
  EXPECT_GE(anchored_checked, 0.95 * plain_checked);
  EXPECT_GT(plain, 0.09);
  EXPECT_LT(anchored, 0.07);
}

// A picture turning about its centre (3 degrees a frame) and shrinking
// (1.5 % a frame), as an object turns in an orbit: translational KLT
// follows the gradient-weighted centre of its window, which turns with the
// picture, so a track slides a little every frame; the affine anchor check
// (klt_anchor_affine) aligns each patch's first appearance, warped, and
// does not. Median distance, after 8 frames, of the tracks that lived
// through them from where their first position was carried.
double MedianDriftOfATurningPicture(bool affine, size_t* checked) {
  TrackerOptions o = SmallOptions();
  o.klt_anchor_frames = affine ? 10 : 0;
  o.klt_anchor_affine = affine;
  FeatureTracker tracker(o);
  const cv::Point2d c((kDecoded.width - 1) / 2.0, (kDecoded.height - 1) / 2.0);
  auto decoded_from_first = [&](int i) {
    const double a = 3.0 * i * M_PI / 180, s = std::pow(0.985, i);
    return cv::Matx22d(s * std::cos(a), -s * std::sin(a), s * std::sin(a), s * std::cos(a));
  };
  std::map<long, Eigen::Vector2d> first;
  FrameTracks last;
  const int frames = 8;
  for (int i = 0; i < frames; ++i) {
    const cv::Matx22d m = decoded_from_first(i).inv();  // texture (first frame) from decoded
    const cv::Vec2d t = -(m * cv::Vec2d(c.x, c.y)) + cv::Vec2d(c.x, c.y);
    const cv::Mat texture_from_decoded = (cv::Mat_<double>(2, 3) << m(0, 0), m(0, 1), t[0], m(1, 0), m(1, 1), t[1]);
    last = tracker.Process(MakeFrame(testing::AnalyticTexture(kDecoded, texture_from_decoded, 2), i, 0.5));
    if (i == 0) first = ById(last);
  }
  const cv::Matx22d carried = decoded_from_first(frames - 1);
  std::vector<double> errors;
  for (const auto& [id, px] : ById(last)) {
    const auto it = first.find(id);
    if (it == first.end()) continue;
    const cv::Vec2d want = carried * cv::Vec2d(it->second.x() - c.x, it->second.y() - c.y);
    errors.push_back((px - Eigen::Vector2d(want[0] + c.x, want[1] + c.y)).norm());
  }
  *checked = errors.size();
  if (errors.empty()) return 1e9;
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

TEST(FeatureTrackerTest, AffineAnchoredTracksDoNotDriftOnATurningPicture) {
  size_t plain_checked = 0, affine_checked = 0;
  const double plain = MedianDriftOfATurningPicture(false, &plain_checked);
  const double affine = MedianDriftOfATurningPicture(true, &affine_checked);
  // Measured: 0.88 px plain (280 tracks), 0.023 affine (278).
  EXPECT_GT(plain_checked, 200u);
  EXPECT_GT(affine_checked, 200u);
  EXPECT_GT(plain, 0.5);
  EXPECT_LT(affine, 0.1);
}

// A region of a still picture changes its look slowly (a cross-fade to
// another texture over 10 frames): every frame-to-frame step is small, so
// KLT keeps its tracks there; against their first appearance the patches
// no longer match, and the affine check's residual, an outlier among the
// frame's, ends them. Tracks elsewhere live on. Counts of the first frame's
// tracks alive at the end, {inside, outside} the region.
std::pair<int, int> SurvivorsOfAChangingRegion(bool affine) {
  TrackerOptions o = SmallOptions();
  o.klt_anchor_frames = affine ? 100 : 0;
  o.klt_anchor_affine = affine;
  FeatureTracker tracker(o);
  const cv::Mat a = NoiseTexture(kDecoded, 3), b = NoiseTexture(kDecoded, 8);
  const cv::Rect region(200, 150, 200, 180);
  std::map<long, Eigen::Vector2d> first;
  FrameTracks last;
  const int frames = 10;
  for (int i = 0; i < frames; ++i) {
    cv::Mat picture = a.clone();
    const double t = static_cast<double>(i) / (frames - 1);
    cv::addWeighted(a(region), 1 - t, b(region), t, 0, picture(region));
    last = tracker.Process(MakeFrame(picture, i, 0.5));
    if (i == 0) first = ById(last);
  }
  // Tracks whose window (17 working px = 34 decoded) overlaps the region's
  // edge see part of the change: counted neither way.
  const cv::Rect inner(region.x + 20, region.y + 20, region.width - 40, region.height - 40);
  const cv::Rect outer(region.x - 20, region.y - 20, region.width + 40, region.height + 40);
  int inside = 0, outside = 0;
  for (const auto& [id, px] : ById(last)) {
    const auto it = first.find(id);
    if (it == first.end()) continue;
    const cv::Point p(static_cast<int>(it->second.x()), static_cast<int>(it->second.y()));
    if (inner.contains(p)) ++inside;
    else if (!outer.contains(p)) ++outside;
  }
  return {inside, outside};
}

TEST(FeatureTrackerTest, AffineAnchorCheckEndsTracksWhosePatchChanged) {
  const auto [plain_inside, plain_outside] = SurvivorsOfAChangingRegion(false);
  const auto [affine_inside, affine_outside] = SurvivorsOfAChangingRegion(true);
  // Measured: plain 24 inside, 247 outside; affine 0 and 247.
  EXPECT_GT(plain_inside, 10);
  EXPECT_LT(affine_inside, 0.2 * plain_inside);
  EXPECT_GT(affine_outside, 0.95 * plain_outside);
}

// Rotation about the decoded image centre, 2 degrees a frame: every step
// moves the tracks as the rotation says. (Translational KLT follows the
// gradient-weighted centre of its window, which rotates about the window
// centre, so a track drifts ~0.1 px a frame against its physical point.)
TEST(FeatureTrackerTest, FollowsRotationAboutTheCentre) {
  const cv::Point2d c((kDecoded.width - 1) / 2.0, (kDecoded.height - 1) / 2.0);
  auto texture_from_decoded = [&](double deg) {
    // texture = R(-deg) (decoded - c): the picture turns by +deg on screen
    // (y down: positive = clockwise).
    const double a = -deg * M_PI / 180;
    const double ca = std::cos(a), sa = std::sin(a);
    return cv::Mat((cv::Mat_<double>(2, 3) << ca, -sa, -(ca * c.x - sa * c.y), sa, ca,
                    -(sa * c.x + ca * c.y)));
  };
  FeatureTracker tracker(SmallOptions());
  const double step = 2.0 * M_PI / 180;
  std::map<long, Eigen::Vector2d> prev;
  for (int i = 0; i < 8; ++i) {
    const FrameTracks t = tracker.Process(
        MakeFrame(testing::AnalyticTexture(kDecoded, texture_from_decoded(2.0 * i), 2), i, 0.5));
    std::vector<double> errors;
    for (const auto& p : t.points) {
      auto it = prev.find(p.track_id);
      if (it == prev.end()) continue;
      const Eigen::Vector2d d(it->second.x() - c.x, it->second.y() - c.y);
      const Eigen::Vector2d want(std::cos(step) * d.x() - std::sin(step) * d.y() + c.x,
                                 std::sin(step) * d.x() + std::cos(step) * d.y() + c.y);
      errors.push_back((p.px - want).norm());
    }
    if (i > 0) {
      ASSERT_GT(errors.size(), 200u) << i;
      std::sort(errors.begin(), errors.end());
      EXPECT_LT(errors[errors.size() / 2], 0.15) << i;
      EXPECT_LT(errors[errors.size() * 9 / 10], 0.4) << i;
    }
    prev = ById(t);
  }
}

// The working -> decoded mapping, checked exactly: a picture mirror-symmetric
// about x = (W - 1) / 2 gives mirrored detections (x, y) and (W - 1 - x, y).
// Dropping the half-pixel terms would put pairs at x + x' = W - 2. (Working
// images narrower than 320 px, where corners are detected at full working
// resolution; wider ones detect on pyrDown's level, which is not symmetric.)
TEST(FeatureTrackerTest, PixelCentreMappingKeepsMirrorSymmetry) {
  cv::Mat half = NoiseTexture({320, 480}, 14);
  cv::Mat mirrored, image;
  cv::flip(half, mirrored, 1);
  cv::hconcat(half, mirrored, image);  // 640 x 480, symmetric
  for (double scale : {0.25, 0.375}) {
    FeatureTracker tracker(SmallOptions());
    const FrameTracks t = tracker.Process(MakeFrame(image, 0, scale));
    ASSERT_GT(t.points.size(), 50u);
    int paired = 0;
    for (const auto& p : t.points) {
      for (const auto& q : t.points) {
        if (std::abs(p.px.x() + q.px.x() - (kDecoded.width - 1)) < 1e-3 &&
            std::abs(p.px.y() - q.px.y()) < 1e-3) {
          ++paired;
          break;
        }
      }
    }
    EXPECT_GT(paired, 0.8 * t.points.size()) << "scale " << scale;
  }
}

// Points whose patch changed (an occluder appeared) fail forward-backward and
// are dropped; the rest continue.
TEST(FeatureTrackerTest, ForwardBackwardRejectsCorruptedPoints) {
  const cv::Mat texture = NoiseTexture({1000, 800}, 3);
  const cv::Mat other = NoiseTexture({1000, 800}, 4);
  FeatureTracker tracker(SmallOptions());
  const FrameTracks t0 = tracker.Process(MakeFrame(Shifted(texture, 0, 0, kDecoded), 0, 0.5));
  cv::Mat next = Shifted(texture, 2.0, 1.0, kDecoded);
  const cv::Rect patch(200, 150, 200, 160);
  Shifted(other, 0, 0, kDecoded)(patch).copyTo(next(patch));
  const FrameTracks t1 = tracker.Process(MakeFrame(next, 1, 0.5));
  const auto after = ById(t1);
  int inside = 0, inside_kept = 0, outside = 0, outside_kept = 0;
  for (const auto& p : t0.points) {
    const bool in = p.px.x() > patch.x + 12 && p.px.x() < patch.br().x - 12 &&
                    p.px.y() > patch.y + 12 && p.px.y() < patch.br().y - 12;
    const bool far = p.px.x() < patch.x - 30 || p.px.x() > patch.br().x + 30 ||
                     p.px.y() < patch.y - 30 || p.px.y() > patch.br().y + 30;
    const bool kept = after.count(p.track_id) > 0;
    if (in) {
      ++inside;
      inside_kept += kept;
    } else if (far) {
      ++outside;
      outside_kept += kept;
      if (kept) {
        const Eigen::Vector2d moved = after.at(p.track_id) - p.px;
        EXPECT_NEAR(moved.x(), 2.0, 0.15);
        EXPECT_NEAR(moved.y(), 1.0, 0.15);
      }
    }
  }
  ASSERT_GT(inside, 10);
  EXPECT_LT(inside_kept, 0.1 * inside + 1);
  EXPECT_GT(outside_kept, 0.9 * outside);
  // New detections fill the patch with fresh ids.
  EXPECT_GT(t1.points.size(), 0.9 * 300);
}

TEST(FeatureTrackerTest, DetectionsAreSpreadOverTheGrid) {
  TrackerOptions o;
  o.max_tracks = 480;
  o.grid_cols = 8;
  o.grid_rows = 6;
  FeatureTracker tracker(o);
  const FrameTracks t = tracker.Process(MakeFrame(NoiseTexture(kDecoded, 5), 0, 1.0));
  std::vector<int> count(48, 0);
  for (const auto& p : t.points) {
    const int cx = std::min(7, static_cast<int>(p.px.x() * 8 / kDecoded.width));
    const int cy = std::min(5, static_cast<int>(p.px.y() * 6 / kDecoded.height));
    ++count[cy * 8 + cx];
  }
  for (int c : count) {
    EXPECT_GE(c, 5);
    EXPECT_LE(c, 10);
  }
  // Ids are unique.
  std::set<long> ids;
  for (const auto& p : t.points) EXPECT_TRUE(ids.insert(p.track_id).second);
}

// A jump of 40% of the width between two frames: KLT cannot follow, ORB
// matching re-links the old ids at the right places.
TEST(FeatureTrackerTest, RecoversAfterALargeJumpWithTheOldIds) {
  const cv::Mat texture = NoiseTexture({1600, 800}, 6);
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  for (int i = 0; i < 4; ++i)
    out.push_back(
        tracker.Process(MakeFrame(Shifted(texture, -1.0 * i, 0, kDecoded, {700, 100}), i, 0.5)));
  const double jump = -0.4 * kDecoded.width;
  const FrameTracks after =
      tracker.Process(MakeFrame(Shifted(texture, -3.0 + jump, 0, kDecoded, {700, 100}), 4, 0.5));
  EXPECT_TRUE(after.recovered);
  EXPECT_EQ(after.shot, 0);
  const auto before = ById(out[3]);
  int relinked = 0;
  for (const auto& p : after.points) {
    auto it = before.find(p.track_id);
    if (it == before.end()) continue;
    ++relinked;
    EXPECT_NEAR(p.px.x() - it->second.x(), jump, 0.2);
    EXPECT_NEAR(p.px.y() - it->second.y(), 0, 0.2);
  }
  EXPECT_GE(relinked, 15);
  // Without recovery the old ids are gone.
  TrackerOptions no_recovery = SmallOptions();
  no_recovery.descriptor_recovery = false;
  no_recovery.descriptor_linking = false;
  FeatureTracker plain(no_recovery);
  FrameTracks last;
  for (int i = 0; i < 4; ++i)
    last = plain.Process(MakeFrame(Shifted(texture, -1.0 * i, 0, kDecoded, {700, 100}), i, 0.5));
  const auto ids_before = ById(last);
  const FrameTracks jumped =
      plain.Process(MakeFrame(Shifted(texture, -3.0 + jump, 0, kDecoded, {700, 100}), 4, 0.5));
  EXPECT_FALSE(jumped.recovered);
  int wrongly_kept = 0;
  for (const auto& p : jumped.points) {
    auto it = ids_before.find(p.track_id);
    if (it != ids_before.end() && std::abs(p.px.x() - it->second.x() - jump) > 2) ++wrongly_kept;
  }
  EXPECT_LE(wrongly_kept, 3);
}

// Decoded view of `texture` turned by `deg` about the decoded centre and
// shifted by (dx, dy) from the view at `origin`.
cv::Mat Turned(const cv::Mat& texture, double deg, double dx, double dy, cv::Point2d origin = {500, 300}) {
  cv::Mat m = cv::getRotationMatrix2D({(kDecoded.width - 1) / 2.0f, (kDecoded.height - 1) / 2.0f}, deg, 1.0);
  m.at<double>(0, 2) += dx - origin.x * m.at<double>(0, 0) - origin.y * m.at<double>(0, 1);
  m.at<double>(1, 2) += dy - origin.x * m.at<double>(1, 0) - origin.y * m.at<double>(1, 1);
  return testing::Warp(texture, m, kDecoded);
}

// Where a point of the view (0, 0, 0) is in the view (deg, dx, dy).
Eigen::Vector2d TurnedPoint(const Eigen::Vector2d& p, double deg, double dx, double dy) {
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  const Eigen::Vector2d centre((kDecoded.width - 1) / 2.0, (kDecoded.height - 1) / 2.0);
  const Eigen::Vector2d q = p - centre;
  return centre + Eigen::Vector2d(c * q.x() + s * q.y(), -s * q.x() + c * q.y()) + Eigen::Vector2d(dx, dy);
}

// Still images far apart (20 degrees of roll and 70 px a step): every pair
// is linked by descriptors, the track ids continue from frame to frame and
// the tracks follow the true motion.
TEST(FeatureTrackerTest, StillsContinueTheirTrackIds) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 41);
  TrackerOptions o = SmallOptions();
  o.stills = true;
  FeatureTracker tracker(o);
  std::map<long, Eigen::Vector2d> first;  // in view 0's coordinates
  for (int i = 0; i < 5; ++i) {
    const double deg = 20.0 * i, dx = 70.0 * i, dy = -30.0 * i;
    const FrameTracks t = tracker.Process(MakeFrame(Turned(texture, deg, dx, dy), i, 0.5));
    EXPECT_EQ(t.shot, 0);
    if (i == 0) {
      EXPECT_EQ(t.boundary, ShotBoundary::kStart);
      for (const auto& p : t.points) first[p.track_id] = p.px;
      EXPECT_GE(first.size(), 100u);
      continue;
    }
    EXPECT_TRUE(t.recovered);
    int continued = 0, off = 0;
    for (const auto& p : t.points) {
      const auto it = first.find(p.track_id);
      if (it == first.end()) continue;
      ++continued;
      if ((TurnedPoint(it->second, deg, dx, dy) - p.px).norm() > 2.0) ++off;
    }
    EXPECT_GE(continued, 40) << "frame " << i;  // ids from frame 0 still alive
    EXPECT_LE(off, continued / 20 + 1) << "frame " << i;
  }
}

// A still that misses part of the picture (the left half covered): the
// next still is linked to the one before it too, and the tracks the covered
// still missed continue there with their ids, on the true positions.
TEST(FeatureTrackerTest, StillsContinueTracksAViewMissed) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 46);
  TrackerOptions o = SmallOptions();
  o.stills = true;
  FeatureTracker tracker(o);
  std::vector<FrameTracks> views;
  for (int i = 0; i < 3; ++i) {
    cv::Mat view = Turned(texture, 10.0 * i, 40.0 * i, 0);
    if (i == 1) view(cv::Rect(0, 0, kDecoded.width / 2, kDecoded.height)).setTo(cv::Scalar(128, 128, 128));
    views.push_back(tracker.Process(MakeFrame(view, i, 0.5)));
    EXPECT_EQ(views.back().shot, 0);
  }
  const auto first = ById(views[0]), covered = ById(views[1]);
  int continued = 0, off = 0;
  for (const auto& p : views[2].points) {
    const auto it = first.find(p.track_id);
    if (it == first.end() || covered.count(p.track_id)) continue;
    ++continued;
    if ((TurnedPoint(it->second, 20.0, 80.0, 0) - p.px).norm() > 2.0) ++off;
  }
  EXPECT_GE(continued, 20);
  EXPECT_LE(off, continued / 20 + 1);
}

// Stills as close as a video's frames (a folder of a video's frames): the
// first link measures a motion within KLT's reach, and KLT (sub-pixel, no
// keypoint noise) takes the following frames, keeping the ids.
TEST(FeatureTrackerTest, StillsAsCloseAsVideoFramesGoBackToKlt) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 45);
  TrackerOptions o = SmallOptions();
  o.stills = true;
  FeatureTracker tracker(o);
  FrameTracks last;
  for (int i = 0; i < 5; ++i) {
    const FrameTracks t = tracker.Process(MakeFrame(Turned(texture, 0, 2.7 * i, 0.4 * i), i, 0.5));
    EXPECT_EQ(t.shot, 0);
    if (i == 1) {
      EXPECT_TRUE(t.recovered);  // linked by descriptors
    }
    EXPECT_FALSE(t.jump) << i;             // ... within KLT's reach
    if (i >= 2) {
      EXPECT_FALSE(t.recovered) << i;  // tracked by KLT
      const auto before = ById(last);
      int continued = 0;
      for (const auto& p : t.points) continued += before.count(p.track_id) > 0;
      EXPECT_GE(continued, 100) << i;
    }
    last = t;
  }
}

// A video of stills (20 degrees of roll and 70 px from its first step on,
// as a folder of photos made into a video): linked as stills, the ids
// continue; without the rule its frames are not stills.
TEST(FeatureTrackerTest, VideoThatJumpsFromItsFirstStepIsLinkedAsStills) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 47);
  for (const bool evidence : {true, false}) {
    TrackerOptions o = SmallOptions();
    o.stills_by_evidence = evidence;
    FeatureTracker tracker(o);
    FrameTracks last;
    for (int i = 0; i < 4; ++i) {
      const FrameTracks t = tracker.Process(MakeFrame(Turned(texture, 20.0 * i, 70.0 * i, -30.0 * i), i, 0.5));
      EXPECT_EQ(t.shot, 0);
      if (i >= 1) {
        EXPECT_EQ(t.still, evidence) << "frame " << i;
      }
      if (i >= 2 && evidence) {
        const auto before = ById(last);
        int continued = 0;
        for (const auto& p : t.points) continued += before.count(p.track_id) > 0;
        EXPECT_GE(continued, 40) << "frame " << i;
      }
      last = t;
    }
  }
}

// The same jump later in a shot (after frames KLT followed) is a video's
// jump (a whip, a lost frame), not stills.
TEST(FeatureTrackerTest, JumpAfterTrackedFramesIsNotStills) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 48);
  FeatureTracker tracker(SmallOptions());
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(tracker.Process(MakeFrame(Turned(texture, 0, 2.0 * i, 0), i, 0.5)).still);
  for (int i = 3; i < 5; ++i)
    EXPECT_FALSE(tracker.Process(MakeFrame(Turned(texture, 20.0 * (i - 2), 70.0 * (i - 2), 0), i, 0.5)).still);
}

// A still that shares nothing with the one before starts a new shot.
TEST(FeatureTrackerTest, StillsThatCannotBeLinkedSplitTheShot) {
  TrackerOptions o = SmallOptions();
  o.stills = true;
  FeatureTracker tracker(o);
  const cv::Mat a = NoiseTexture({1600, 1200}, 42), b = NoiseTexture({1600, 1200}, 43);
  tracker.Process(MakeFrame(Turned(a, 0, 0, 0), 0, 0.5));
  const FrameTracks same = tracker.Process(MakeFrame(Turned(a, 10, 40, 0), 1, 0.5));
  EXPECT_EQ(same.boundary, ShotBoundary::kNone);
  const FrameTracks other = tracker.Process(MakeFrame(Turned(b, 0, 0, 0), 2, 0.5));
  EXPECT_EQ(other.boundary, ShotBoundary::kCut);
  EXPECT_EQ(other.shot, 1);
}

// Stills that come round: shot 0 sees picture a, a view that shares
// nothing with it splits (shot 1, picture b), then a view showing b on its
// left and a (near view 0) on its right links to shot 1's last view and,
// across the split, to shot 0's views: it reports the link and continues
// view 0's tracks on their true positions. A view of a third picture links
// to neither: a shot of its own, no link to an earlier shot.
TEST(FeatureTrackerTest, StillsLinkAcrossASplitToAnEarlierShot) {
  TrackerOptions o = SmallOptions();
  o.stills = true;
  FeatureTracker tracker(o);
  const cv::Mat a = NoiseTexture({1600, 1200}, 51), b = NoiseTexture({1600, 1200}, 52),
                c = NoiseTexture({1600, 1200}, 53);
  const FrameTracks view0 = tracker.Process(MakeFrame(Turned(a, 0, 0, 0), 0, 0.5));
  tracker.Process(MakeFrame(Turned(a, 10, 40, 0), 1, 0.5));
  EXPECT_EQ(tracker.Process(MakeFrame(Turned(b, 0, 0, 0), 2, 0.5)).shot, 1);
  const FrameTracks b1 = tracker.Process(MakeFrame(Turned(b, 20, 70, -30), 3, 0.5));
  EXPECT_TRUE(b1.earlier_shot_links.empty());
  cv::Mat both = Turned(b, 40, 140, -60).clone();
  const cv::Rect right(kDecoded.width / 2, 0, kDecoded.width - kDecoded.width / 2, kDecoded.height);
  Turned(a, 4, 20, 0)(right).copyTo(both(right));
  const FrameTracks round = tracker.Process(MakeFrame(both, 4, 0.5));
  EXPECT_EQ(round.shot, 1);
  ASSERT_FALSE(round.earlier_shot_links.empty());
  for (const auto& link : round.earlier_shot_links) {
    EXPECT_EQ(link.shot, 0);
    EXPECT_GE(link.verified, 15);
  }
  const auto first = ById(view0);
  int continued = 0, off = 0;
  for (const auto& p : round.points) {
    const auto it = first.find(p.track_id);
    if (it == first.end()) continue;
    ++continued;
    if ((TurnedPoint(it->second, 4, 20, 0) - p.px).norm() > 2.0) ++off;
  }
  EXPECT_GE(continued, 15);
  EXPECT_LE(off, continued / 20 + 1);
  const FrameTracks other = tracker.Process(MakeFrame(Turned(c, 0, 0, 0), 5, 0.5));
  EXPECT_EQ(other.shot, 2);
  EXPECT_TRUE(other.earlier_shot_links.empty());
}

// A video that rolls 60 degrees from one frame to the next (KLT loses it,
// the upright ORB re-linker too): the descriptor link carries the old ids
// onto the true positions; without it they are gone.
TEST(FeatureTrackerTest, SuddenRollIsLinkedByDescriptors) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 44);
  for (const bool linking : {true, false}) {
    TrackerOptions o = SmallOptions();
    o.descriptor_linking = linking;
    FeatureTracker tracker(o);
    FrameTracks last;
    for (int i = 0; i < 3; ++i) last = tracker.Process(MakeFrame(Turned(texture, 0, 2.0 * i, 0), i, 0.5));
    const FrameTracks rolled = tracker.Process(MakeFrame(Turned(texture, 60, 4.0, 0), 3, 0.5));
    const auto before = ById(last);
    int continued = 0, off = 0;
    for (const auto& p : rolled.points) {
      const auto it = before.find(p.track_id);
      if (it == before.end()) continue;
      ++continued;
      const Eigen::Vector2d at_zero = it->second - Eigen::Vector2d(4.0, 0);
      if ((TurnedPoint(at_zero, 60, 4.0, 0) - p.px).norm() > 2.0) ++off;
    }
    EXPECT_FALSE(last.jump);
    if (linking) {
      EXPECT_TRUE(rolled.recovered);
      EXPECT_TRUE(rolled.jump);  // beyond KLT's reach: the path is not continuous here
      EXPECT_EQ(rolled.shot, 0);
      EXPECT_GE(continued, 40);
      EXPECT_LE(off, continued / 20 + 1);
    } else {
      EXPECT_LE(continued - off, 3);
    }
  }
}

// A video that jumps away (60 degrees of roll and 250 px: KLT loses it)
// and back near where KLT followed it: the frame back is linked to the jump
// before it and to the shot's earlier frames, so the tracks the jump frame
// did not see continue with their ids, on the true positions.
TEST(FeatureTrackerTest, JumpBackContinuesTracksOfTheFramesBeforeTheJump) {
  const cv::Mat texture = NoiseTexture({1600, 1200}, 49);
  FeatureTracker tracker(SmallOptions());
  FrameTracks last;
  for (int i = 0; i < 3; ++i) last = tracker.Process(MakeFrame(Turned(texture, 0, 2.0 * i, 0), i, 0.5));
  const FrameTracks away = tracker.Process(MakeFrame(Turned(texture, 60, 250, 0), 3, 0.5));
  const FrameTracks back = tracker.Process(MakeFrame(Turned(texture, 0, 10, 0), 4, 0.5));
  EXPECT_TRUE(away.jump);
  EXPECT_TRUE(back.jump);
  EXPECT_EQ(back.shot, 0);
  const auto before = ById(last), seen_away = ById(away);
  int continued = 0, off = 0;
  for (const auto& p : back.points) {
    const auto it = before.find(p.track_id);
    if (it == before.end() || seen_away.count(p.track_id)) continue;
    ++continued;
    if ((it->second + Eigen::Vector2d(6.0, 0) - p.px).norm() > 2.0) ++off;
  }
  EXPECT_GE(continued, 40);
  EXPECT_LE(off, continued / 20 + 1);
}

// A pan out and back over a wide picture (16 px a frame, within KLT's
// reach): the tracks of the first frames leave the picture on the way out,
// and on the way back the same part is seen again under new ids. Revisit
// links continue the first frames' ids there, at the places the known
// shift predicts.
std::vector<FrameTracks> PanOutAndBack(const TrackerOptions& o, int out_frames, bool back) {
  const cv::Mat texture = NoiseTexture({1900, 700}, 57);
  FeatureTracker tracker(o);
  std::vector<FrameTracks> frames;
  const int n = back ? 2 * out_frames : out_frames;
  for (int i = 0; i <= n; ++i) {
    const int at = i <= out_frames ? i : 2 * out_frames - i;  // frames from the start
    frames.push_back(tracker.Process(MakeFrame(Shifted(texture, -16.0 * at, 0, kDecoded), i, 0.5)));
  }
  return frames;
}

TEST(FeatureTrackerTest, RevisitLinksContinueTheIdsOfTheFirstPass) {
  TrackerOptions o = SmallOptions();
  o.revisit_links = true;
  const int out = 60;
  const std::vector<FrameTracks> on = PanOutAndBack(o, out, true);
  const std::vector<FrameTracks> off = PanOutAndBack(SmallOptions(), out, true);
  const auto first = ById(on[2]);  // frame 2: the view of frames 0-4
  const auto count_first = [&](const FrameTracks& t, int* off_px) {
    int n = 0;
    for (const auto& p : t.points) {
      const auto it = first.find(p.track_id);
      if (it == first.end()) continue;
      ++n;
      // Frame 2 showed the picture 32 px further left than the start.
      const double at = t.index <= out ? t.index : 2 * out - t.index;
      if ((it->second + Eigen::Vector2d(16.0 * (2 - at), 0) - p.px).norm() > 1.5) ++*off_px;
    }
    return n;
  };
  int off_px = 0, ignored = 0;
  EXPECT_EQ(count_first(on[out], &ignored), 0);  // gone at the far end
  EXPECT_EQ(count_first(off.back(), &ignored), 0);
  const int continued = count_first(on.back(), &off_px);
  EXPECT_GE(continued, 30);
  EXPECT_LE(off_px, continued / 20 + 1);
  for (const FrameTracks& t : on) EXPECT_EQ(t.shot, 0);
}

// Degenerate: a pan that never comes back. No earlier view shows the
// picture again, so no revisit link verifies, and the tracks are exactly
// those without the option.
TEST(FeatureTrackerTest, RevisitLinksChangeNothingWithoutARevisit) {
  TrackerOptions o = SmallOptions();
  o.revisit_links = true;
  const std::vector<FrameTracks> on = PanOutAndBack(o, 70, false);
  const std::vector<FrameTracks> off = PanOutAndBack(SmallOptions(), 70, false);
  ASSERT_EQ(on.size(), off.size());
  for (size_t i = 0; i < on.size(); ++i) {
    ASSERT_EQ(on[i].points.size(), off[i].points.size()) << "frame " << i;
    for (size_t k = 0; k < on[i].points.size(); ++k) {
      EXPECT_EQ(on[i].points[k].track_id, off[i].points[k].track_id);
      EXPECT_EQ(on[i].points[k].px, off[i].points[k].px);
    }
  }
}

TEST(FeatureTrackerTest, CutDropsAllTracksAndStartsNewIds) {
  const cv::Mat a = NoiseTexture({1000, 800}, 7, {0.8, 0.0, -0.6});
  const cv::Mat b = NoiseTexture({1000, 800}, 8, {-0.6, 0.2, 0.8});
  FeatureTracker tracker(SmallOptions());
  long max_id = -1;
  for (int i = 0; i < 20; ++i) {
    const cv::Mat& tex = i < 10 ? a : b;
    const FrameTracks t =
        tracker.Process(MakeFrame(Shifted(tex, 1.5 * i, 0.5 * i, kDecoded), i, 0.5));
    if (i == 10) {
      EXPECT_EQ(t.boundary, ShotBoundary::kCut);
      EXPECT_EQ(t.shot, 1);
      for (const auto& p : t.points) EXPECT_GT(p.track_id, max_id);
      EXPECT_GT(t.points.size(), 250u);
    } else {
      EXPECT_EQ(t.boundary, i == 0 ? ShotBoundary::kStart : ShotBoundary::kNone) << i;
      EXPECT_EQ(t.shot, i < 10 ? 0 : 1);
    }
    for (const auto& p : t.points) max_id = std::max(max_id, p.track_id);
  }
}

// A pan (3 decoded px a frame) whose frames 10 to 10 + blurred - 1 are
// blurred past what KLT, the ORB re-links and the SIFT probe can follow (a
// blur burst inside a take), then sharp again: the picture is `after` from
// then on (the same texture: the take goes on; another one: a cut).
// `flash`: the burst's frames also washed out towards white (0.4 x + 150),
// which moves the histogram past the hard cut's threshold.
std::vector<FrameTracks> TrackBlurBurst(const cv::Mat& before, const cv::Mat& after, int blurred,
                                        const TrackerOptions& options, bool flash = false) {
  FeatureTracker tracker(options);
  std::vector<FrameTracks> out;
  for (int i = 0; i < 20 + blurred; ++i) {
    cv::Mat picture = Shifted(i < 10 + blurred ? before : after, 3.0 * i, 0, kDecoded);
    if (i >= 10 && i < 10 + blurred) cv::GaussianBlur(picture, picture, cv::Size(0, 0), 12);
    if (flash && i >= 10 && i < 10 + blurred) picture.convertTo(picture, -1, 0.4, 150);
    out.push_back(tracker.Process(MakeFrame(picture, i, 0.5)));
  }
  return out;
}

// How many of frame `a`'s tracks frame `b` continues within 1 decoded px of
// where the pan takes them (3 px a frame to the right).
int ContinuedOnThePan(const FrameTracks& a, const FrameTracks& b) {
  const std::map<long, Eigen::Vector2d> at_a = ById(a);
  int n = 0;
  for (const TrackPoint& p : b.points) {
    const auto it = at_a.find(p.track_id);
    if (it != at_a.end() &&
        (p.px - it->second - Eigen::Vector2d(3.0 * (b.index - a.index), 0)).norm() < 1)
      ++n;
  }
  return n;
}

// Inside the burst no track survives from frame 9; the first sharp frame is
// linked back to frame 9 by descriptors and continues its tracks, so the
// estimator keeps one shot. Without the bridge, nothing ties them.
TEST(FeatureTrackerTest, BlurBurstIsBridgedToTheFrameBeforeIt) {
  const cv::Mat texture = NoiseTexture({1000, 800}, 31);
  const std::vector<FrameTracks> out = TrackBlurBurst(texture, texture, 4, SmallOptions());
  for (const FrameTracks& t : out) {
    EXPECT_EQ(t.shot, 0) << t.index;
    EXPECT_EQ(t.bridging, t.index >= 10 && t.index < 14) << t.index;
  }
  EXPECT_EQ(ContinuedOnThePan(out[9], out[10]), 0) << "the blur must break tracking for this test";
  EXPECT_TRUE(out[14].recovered);
  EXPECT_GE(ContinuedOnThePan(out[9], out[14]), 40);
  TrackerOptions off = SmallOptions();
  off.bridge_breaks = false;
  const std::vector<FrameTracks> plain = TrackBlurBurst(texture, texture, 4, off);
  EXPECT_LT(ContinuedOnThePan(plain[9], plain[14]), 12);
  for (const FrameTracks& t : plain) EXPECT_FALSE(t.bridging);
}

// A flash with the blur: the shot detector cuts on the histogram, but the
// picture continues the last one; the first sharp frame links back to the
// frame before the flash, and the cuts are withdrawn (the same shot).
TEST(FeatureTrackerTest, CutOnAFlashIsWithdrawnWhenTheTakeGoesOn) {
  const cv::Mat texture = NoiseTexture({1000, 800}, 31);
  const std::vector<FrameTracks> out = TrackBlurBurst(texture, texture, 4, SmallOptions(), true);
  EXPECT_EQ(out[10].boundary, ShotBoundary::kCut) << "the flash must cut for this test";
  for (const FrameTracks& t : out) EXPECT_EQ(t.bridging, t.index >= 10 && t.index < 14) << t.index;
  for (size_t i = 14; i < out.size(); ++i) {
    EXPECT_EQ(out[i].shot, 0) << i;
    EXPECT_EQ(out[i].boundary, ShotBoundary::kNone) << i;
  }
  EXPECT_GE(ContinuedOnThePan(out[9], out[14]), 40);
  TrackerOptions off = SmallOptions();
  off.bridge_breaks = false;
  EXPECT_GE(TrackBlurBurst(texture, texture, 4, off, true).back().shot, 1);
}

// A cut right after the burst (another picture with the same colours):
// no track of frame 9 reaches the new picture (here the shot detector's
// look-alike cut cues see the cut; the bridge ends with the shot).
TEST(FeatureTrackerTest, CutRightAfterABlurBurstIsNotBridged) {
  const std::vector<FrameTracks> out = TrackBlurBurst(
      NoiseTexture({1000, 800}, 31), NoiseTexture({1000, 800}, 32), 4, SmallOptions());
  const std::map<long, Eigen::Vector2d> before = ById(out[9]);
  for (size_t i = 10; i < out.size(); ++i) {
    for (const TrackPoint& p : out[i].points) EXPECT_EQ(before.count(p.track_id), 0u) << i;
    EXPECT_EQ(out[i].bridging, i < 14) << i;
  }
  EXPECT_EQ(out.back().shot, 1);
}

// A burst longer than the bridge (16 frames at 24 fps): the later frames
// are linked back for half a second, then the tracker gives up and the
// sharp frames after the burst do not continue frame 9's tracks (the
// estimator splits where tracking broke, as without the bridge). A later
// collapse inside the blur is a break of its own.
TEST(FeatureTrackerTest, BlurBurstLongerThanTheBridgeIsNotBridged) {
  const cv::Mat texture = NoiseTexture({1000, 800}, 31);
  const std::vector<FrameTracks> out = TrackBlurBurst(texture, texture, 16, SmallOptions());
  EXPECT_TRUE(out[10].bridging);
  size_t gave_up = 11;
  while (gave_up < out.size() && out[gave_up].bridging) ++gave_up;
  ASSERT_LT(gave_up, out.size());
  EXPECT_LE(out[gave_up].time_s - out[10].time_s, 0.5 + 1 / 24.0 + 1e-9);
  for (const FrameTracks& t : out) EXPECT_EQ(t.shot, 0) << t.index;
  EXPECT_LT(ContinuedOnThePan(out[9], out[26]), 12);
}

// A cut between two views of the same set: the histograms stay close (under
// the cut threshold), but tracking collapses at once and the descriptors find
// nothing in common, on a frame whose histogram distance jumps well above the
// pan's steady change. That is a cut.
TEST(FeatureTrackerTest, CutBetweenTwoViewsOfTheSameSceneSplits) {
  const cv::Mat scene = NoiseTexture({3200, 800}, 23);
  const auto view = [&](int i) {
    // Shot 0 pans right at 4 px/frame; shot 1 shows another part of the set,
    // 1600 px away (no overlap), panning the other way.
    const double x = i < 12 ? 4.0 * i : 1600 - 4.0 * (i - 12);
    return MakeFrame(Shifted(scene, -x, 0, kDecoded, {200, 100}), i, 0.5);
  };
  ShotDetector histograms_only;
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  for (int i = 0; i < 24; ++i) {
    const Frame frame = view(i);
    const ShotDecision d = histograms_only.Update(frame);
    EXPECT_EQ(d.boundary, ShotBoundary::kNone) << "the histograms alone must not see it, " << i;
    if (i == 12) {
      EXPECT_LT(d.distance, SmallOptions().cut_threshold);
      EXPECT_TRUE(d.spike);
    }
    out.push_back(tracker.Process(frame));
  }
  long max_id_before = -1;
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(out[i].shot, 0) << i;
    for (const auto& p : out[i].points) max_id_before = std::max(max_id_before, p.track_id);
  }
  EXPECT_EQ(out[12].boundary, ShotBoundary::kCut);
  EXPECT_FALSE(out[12].recovered);
  EXPECT_GT(out[12].points.size(), 250u) << "the new shot is tracked from its first frame";
  for (const auto& p : out[12].points) EXPECT_GT(p.track_id, max_id_before);
  for (int i = 12; i < 24; ++i) EXPECT_EQ(out[i].shot, 1) << i;
  for (int i = 13; i < 24; ++i) EXPECT_EQ(out[i].boundary, ShotBoundary::kNone) << i;
  EXPECT_GT(out.back().quality, 0.8);
}

// A whip pan across changing colours with motion blur: KLT collapses and
// the histograms change on every frame, but steadily, with no spike on the
// collapsing frames. One shot.
// Still for 8 frames, 2400 px (decoded) in 16 frames on an eased profile
// (peak ~240 px/frame), still again. 180-degree shutter: the motion over the
// middle half of the frame interval, as a horizontal box blur (exact for a
// translation, up to the border).
double WhipPosition(double t) {
  const double s = std::clamp((t - 8) / 16.0, 0.0, 1.0);
  return 2400.0 * (0.5 - 0.5 * std::cos(M_PI * s));
}

std::vector<FrameTracks> TrackBlurredWhip(const TrackerOptions& options) {
  const cv::Mat wide = BlendedAcross(NoiseTexture({4000, 800}, 24, {-0.8, -0.6, -0.4}),
                                     NoiseTexture({4000, 800}, 25, {0.6, 0.8, 0.9}), 1000, 2000);
  FeatureTracker tracker(options);
  std::vector<FrameTracks> out;
  for (int i = 0; i < 30; ++i) {
    cv::Mat img = Shifted(wide, -WhipPosition(i), 0, kDecoded, {200, 100});
    const int blur = static_cast<int>(std::lround(WhipPosition(i + 0.25) - WhipPosition(i - 0.25)));
    if (blur > 1) cv::blur(img, img, cv::Size(blur, 1));
    out.push_back(tracker.Process(MakeFrame(img, i, 0.5)));
  }
  return out;
}

// Without the constant-velocity start KLT collapses in the blur, and the
// collapse must not be read as a cut.
TEST(FeatureTrackerTest, BlurredWhipPanIsNotACut) {
  TrackerOptions options = SmallOptions();
  options.klt_predict = false;
  const std::vector<FrameTracks> out = TrackBlurredWhip(options);
  double min_quality = 1;
  for (const auto& t : out) {
    EXPECT_EQ(t.shot, 0) << t.index;
    EXPECT_TRUE(t.boundary == ShotBoundary::kNone || t.index == 0) << t.index;
    min_quality = std::min(min_quality, t.quality);
  }
  EXPECT_LT(min_quality, 0.15) << "tracking must collapse in the blur for this test to mean anything";
}

// With it (the default), the same whip keeps its tracks through the blur,
// and they move by the true shift (horizontal, up to the blur's own error).
// For each track in both: how far its motion from `before` to `now` is from
// a horizontal shift of the picture by -shift decoded px.
void AppendMotionErrors(const FrameTracks& before, const FrameTracks& now, double shift,
                        std::vector<double>* error_px) {
  for (const TrackPoint& p : now.points)
    for (const TrackPoint& q : before.points)
      if (q.track_id == p.track_id) {
        error_px->push_back(std::hypot(p.px.x() - q.px.x() + shift, p.px.y() - q.px.y()));
        break;
      }
}

TEST(FeatureTrackerTest, BlurredWhipPanIsTrackedFromItsLastMotion) {
  const std::vector<FrameTracks> out = TrackBlurredWhip(SmallOptions());
  double min_quality = 1;
  std::vector<double> error_px;
  for (size_t f = 1; f < out.size(); ++f) {
    EXPECT_EQ(out[f].shot, 0) << f;
    min_quality = std::min(min_quality, out[f].quality);
    AppendMotionErrors(out[f - 1], out[f], WhipPosition(f) - WhipPosition(f - 1.0), &error_px);
  }
  EXPECT_GT(min_quality, 0.15) << "tracks survive every frame of the whip";
  ASSERT_GT(error_px.size(), 1000u);
  std::nth_element(error_px.begin(), error_px.begin() + error_px.size() / 2, error_px.end());
  EXPECT_LT(error_px[error_px.size() / 2], 1.0) << "median error of the per-frame motion, decoded px";
}

// The same whip with every other frame skipped by the decoder (index gaps of
// 2, --skip-nonref): its displacements per decoded frame double, and it
// speeds up faster than the prediction trusts. The prediction scales with
// the gap, and the collapse at the start is retried from the last motion
// kept speeding up: tracks survive every decoded frame, with their true
// motion, and no cut is read.
TEST(FeatureTrackerTest, BlurredWhipPanWithSkippedFramesIsTracked) {
  const cv::Mat wide = BlendedAcross(NoiseTexture({4000, 800}, 24, {-0.8, -0.6, -0.4}),
                                     NoiseTexture({4000, 800}, 25, {0.6, 0.8, 0.9}), 1000, 2000);
  // 0.4 of the whip above: at its fastest a decoded frame moves by ~30 % of
  // the picture's width, as an 80 deg whip pan decoded every other frame.
  const auto position = [](double t) { return 0.4 * WhipPosition(t); };
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  std::vector<double> error_px;
  double min_quality = 1;
  for (int i = 0; i < 30; i += 2) {
    cv::Mat img = Shifted(wide, -position(i), 0, kDecoded, {200, 100});
    const int blur = static_cast<int>(std::lround(position(i + 0.25) - position(i - 0.25)));
    if (blur > 1) cv::blur(img, img, cv::Size(blur, 1));
    Frame frame = MakeFrame(img, i, 0.5);
    if (i > 0) frame.skipped_before_s = {(i - 1) / 24.0};
    out.push_back(tracker.Process(frame));
    const FrameTracks& now = out.back();
    EXPECT_EQ(now.shot, 0) << i;
    if (i == 0) continue;
    min_quality = std::min(min_quality, now.quality);
    AppendMotionErrors(out[out.size() - 2], now, position(i) - position(i - 2.0), &error_px);
  }
  EXPECT_GT(min_quality, 0.15) << "tracks survive every decoded frame of the whip";
  ASSERT_GT(error_px.size(), 500u);
  std::nth_element(error_px.begin(), error_px.begin() + error_px.size() / 2, error_px.end());
  EXPECT_LT(error_px[error_px.size() / 2], 1.0) << "median error of the motion per decoded frame, px";
}

// Tracks continued from the previous frame on a texture shifted by
// position(f) decoded px (horizontally), and how many are off by > 1 px.
struct Continued {
  int matched = 0, wrong = 0;
};

std::vector<Continued> TrackShifts(const std::function<double(int)>& position, int frames, bool predict) {
  const cv::Mat wide = NoiseTexture({3000, 800}, 27, {0.2, -0.1, 0.3});
  TrackerOptions options = SmallOptions();
  options.klt_predict = predict;
  FeatureTracker tracker(options);
  std::vector<FrameTracks> out;
  std::vector<Continued> counts(frames);
  for (int f = 0; f < frames; ++f) {
    out.push_back(tracker.Process(MakeFrame(Shifted(wide, -position(f), 0, kDecoded, {200, 100}), f, 0.5)));
    EXPECT_EQ(out[f].shot, 0) << f;
    if (f == 0) continue;
    const double shift = position(f) - position(f - 1);
    for (const TrackPoint& now : out[f].points)
      for (const TrackPoint& before : out[f - 1].points)
        if (before.track_id == now.track_id) {
          ++counts[f].matched;
          counts[f].wrong += std::hypot(now.px.x() - before.px.x() + shift, now.px.y() - before.px.y()) > 1.0;
          break;
        }
  }
  return counts;
}

// The prediction's hard case: a fast pan (80 decoded px a frame, over a KLT
// window at the half-size working image) that stops dead, and starts again.
// At the stop every search starts 40 working px off. Few tracks may pass the
// forward-backward check on a look-alike (a start from zero has the same
// risk: the first frames of each move); the prediction must not add to them,
// and enough tracks must survive the stop.
TEST(FeatureTrackerTest, FastPanStoppingDeadIsTrackedWithoutMoreFalseMatches) {
  const auto position = [](int f) { return f < 6 ? 80.0 * f : f < 10 ? 400.0 : 400.0 + 80.0 * (f - 9); };
  const std::vector<Continued> with = TrackShifts(position, 14, true), without = TrackShifts(position, 14, false);
  int wrong_with = 0, wrong_without = 0;
  for (int f = 1; f < 14; ++f) {
    EXPECT_GT(with[f].matched, 100) << "frame " << f;
    EXPECT_LE(with[f].wrong, 0.02 * with[f].matched) << "frame " << f;
    wrong_with += with[f].wrong;
    wrong_without += without[f].wrong;
  }
  EXPECT_LE(with[6].wrong, 1) << "the stop";
  EXPECT_LT(wrong_with, wrong_without);
}

// A violent shake, 60 decoded px (30 working, over a KLT window) back and
// forth every frame: the last motion is no guide to the next, so KLT starts
// from zero motion as without the prediction and keeps every track (with
// the last motion as the start it kept ~90 of 270 a frame).
TEST(FeatureTrackerTest, ShakeBackAndForthIsTrackedAsWithoutPrediction) {
  const auto position = [](int f) { return (f % 2) ? 60.0 : 0.0; };
  const std::vector<Continued> with = TrackShifts(position, 12, true), without = TrackShifts(position, 12, false);
  for (int f = 1; f < 12; ++f) {
    EXPECT_GT(without[f].matched, 250) << "frame " << f;
    EXPECT_GE(with[f].matched, without[f].matched) << "frame " << f;
    EXPECT_EQ(with[f].wrong, 0) << "frame " << f;
  }
}

// A fade down to a dim (not blank) picture and back on a panning camera: the
// histograms change gradually, tracks may die, one shot.
TEST(FeatureTrackerTest, FadeThatStaysAboveBlackIsNotACut) {
  const cv::Mat a = NoiseTexture({1600, 800}, 26, {0.3, 0.0, -0.3});
  FeatureTracker tracker(SmallOptions());
  for (int i = 0; i < 36; ++i) {
    // 10..19 down to 25 % brightness, 20..29 back up.
    double gain = 1;
    if (i >= 10 && i < 20) gain = 1 - 0.075 * (i - 9);
    if (i >= 20 && i < 30) gain = 0.25 + 0.075 * (i - 19);
    cv::Mat img = Shifted(a, -3.0 * i, 0, kDecoded);
    img.convertTo(img, -1, gain, 0);
    const FrameTracks t = tracker.Process(MakeFrame(img, i, 0.5));
    EXPECT_FALSE(t.blank) << i;
    EXPECT_EQ(t.shot, 0) << i;
  }
}

// Lucas-Kanade assumes constant brightness: in a fade (the picture scaled
// by 7.5 % a frame, with grain) under light that falls off across the
// picture, the frames are tracked at the last one's contrast, so the pan's
// 3 px a frame are read as outside the fade.
TEST(FeatureTrackerTest, PanThroughAFadeIsReadAsOutsideIt) {
  const cv::Mat a = NoiseTexture({1600, 800}, 26, {0.3, 0.0, -0.3});
  // Light falling off across the picture (vignetting, a lamp): where the
  // picture's brightness has a slope, a change of gain biases LK along it.
  cv::Mat light(kDecoded, CV_32FC3);
  for (int x = 0; x < kDecoded.width; ++x)
    light.col(x).setTo(cv::Scalar::all(1.0 - 0.6 * x / kDecoded.width));
  cv::RNG rng(5);
  TrackerOptions o = SmallOptions();
  o.match_fade_contrast = true;
  FeatureTracker tracker(o);
  std::map<long, Eigen::Vector2d> last;
  std::vector<double> fade_steps;
  for (int i = 0; i < 30; ++i) {
    double gain = 1;
    if (i >= 10 && i < 20) gain = 1 - 0.075 * (i - 9);  // 10..19 down to 25 %, 20..29 back up
    if (i >= 20) gain = std::min(1.0, 0.25 + 0.075 * (i - 19));
    cv::Mat img = Shifted(a, -3.0 * i, 0, kDecoded);
    img.convertTo(img, CV_32FC3);
    cv::multiply(img, light, img, gain);
    cv::Mat grain(img.size(), CV_32FC3);
    rng.fill(grain, cv::RNG::NORMAL, 0, 3);  // film grain, 3 levels
    img += grain;
    img.convertTo(img, CV_8UC3);
    const auto now = ById(tracker.Process(MakeFrame(img, i, 0.5)));
    if (i >= 11 && i < 30)
      for (const auto& [id, px] : now)
        if (last.count(id)) fade_steps.push_back(px.x() - last.at(id).x());
    last = now;
  }
  ASSERT_GT(fade_steps.size(), 1000u);
  std::sort(fade_steps.begin(), fade_steps.end());
  EXPECT_NEAR(fade_steps[fade_steps.size() / 2], -3.0, 0.006);  // 0.013 without the matching
  double sum = 0;
  for (double d : fade_steps) sum += d;
  EXPECT_NEAR(sum / fade_steps.size(), -3.0, 0.012);  // 0.024 without
}

// Frames of a pan (16 px a frame, blurred along it as a fast pan is) under
// a vignetting of `corner_falloff` at the corners; the median step of the
// tracks near the left and right edges (|x - W/2| > 0.3 W) over the true
// step, from frame 12 on; `points` receives the last frame's tracks.
double EdgeStepRatio(bool flat_field, double corner_falloff, std::map<long, Eigen::Vector2d>* points = nullptr) {
  cv::Mat texture = NoiseTexture({1400, 480}, 12);
  cv::blur(texture, texture, cv::Size(21, 1));
  cv::Mat field(kDecoded, CV_32FC3);
  const double cx = 0.5 * kDecoded.width, cy = 0.5 * kDecoded.height;
  for (int y = 0; y < kDecoded.height; ++y)
    for (int x = 0; x < kDecoded.width; ++x)
      field.at<cv::Vec3f>(y, x) = cv::Vec3f::all(
          static_cast<float>(1 - corner_falloff * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy)));
  TrackerOptions o = SmallOptions();
  o.flat_field_vignetting = flat_field;
  FeatureTracker tracker(o);
  std::map<long, Eigen::Vector2d> last;
  std::vector<double> ratios;
  const double step = 16;
  for (int i = 0; i < 40; ++i) {
    cv::Mat img = Shifted(texture, -step * i, 0, kDecoded);
    img.convertTo(img, CV_32FC3);
    cv::multiply(img, field, img);
    img.convertTo(img, CV_8UC3);
    const auto now = ById(tracker.Process(MakeFrame(img, i, 0.5)));
    if (i >= 12)
      for (const auto& [id, px] : now)
        if (last.count(id) && std::abs(last.at(id).x() - cx) > 0.3 * kDecoded.width)
          ratios.push_back((last.at(id).x() - px.x()) / step);
    last = now;
  }
  if (points) *points = last;
  EXPECT_GT(ratios.size(), 500u);
  std::sort(ratios.begin(), ratios.end());
  return ratios[ratios.size() / 2];
}

// Vignetting's slope inside a KLT window does not move with the texture,
// and LK reads the picture's edges moving short; the tracker finds the field
// from its tracks' brightness and tracks flat-fielded frames.
TEST(FeatureTrackerTest, VignettedPanIsReadRightAtTheEdges) {
  const double off = EdgeStepRatio(false, 0.4), on = EdgeStepRatio(true, 0.4);
  EXPECT_LT(off, 0.985);         // 0.976 measured
  EXPECT_NEAR(on, 1.0, 0.004);  // 1.000
}

// Without vignetting nothing is found: the tracks are the same to the bit.
TEST(FeatureTrackerTest, NoVignettingChangesNothing) {
  std::map<long, Eigen::Vector2d> off, on;
  EdgeStepRatio(false, 0.0, &off);
  EdgeStepRatio(true, 0.0, &on);
  EXPECT_EQ(off, on);
}

TEST(ContrastMatched, MatchesAFadeAndLeavesBlurAndNoiseAlone) {
  EXPECT_TRUE(IsFadeStep(1.08, 1.08));    // fading out: the reference is brighter
  EXPECT_TRUE(IsFadeStep(0.9, 0.92));     // fading in
  EXPECT_FALSE(IsFadeStep(1.01, 1.01));   // grain, compression
  EXPECT_FALSE(IsFadeStep(1.0, 1.2));     // motion blur: contrast alone
  EXPECT_FALSE(IsFadeStep(1.1, 0.9));     // new content: opposite ways
  EXPECT_FALSE(IsFadeStep(1.3, 1.05));    // not one factor
  EXPECT_FALSE(IsFadeStep(std::nan(""), 1.1));
  const cv::Mat a = NoiseTexture({200, 100}, 3);
  cv::Mat gray, dim;
  cv::cvtColor(a, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(dim, -1, 0.5, 0);
  cv::Scalar mean, stddev, dim_mean, dim_stddev;
  cv::meanStdDev(gray, mean, stddev);
  cv::meanStdDev(dim, dim_mean, dim_stddev);
  double gain = 0;
  const cv::Mat matched = ContrastMatched(dim, dim_mean[0], dim_stddev[0], mean[0], stddev[0], &gain);
  EXPECT_NEAR(gain, 2.0, 0.02);
  EXPECT_LT(cv::norm(matched, gray, cv::NORM_INF), 2.5);  // rounding of the dim copy, doubled
  // Within 2 %: the frame itself, not a copy.
  const cv::Mat same = ContrastMatched(gray, mean[0], stddev[0], mean[0] * 1.01, stddev[0] * 1.01, &gain);
  EXPECT_EQ(same.data, gray.data);
  EXPECT_EQ(gain, 1.0);
  // A blank frame (no contrast) is left alone.
  const cv::Mat black(50, 50, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(ContrastMatched(black, 0, 0, mean[0], stddev[0], &gain).data, black.data);
}

TEST(FeatureTrackerTest, BlankFramesAreFlaggedAndNotTracked) {
  const cv::Mat a = NoiseTexture({1000, 800}, 9);
  FeatureTracker tracker(SmallOptions());
  const cv::Mat black(kDecoded, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int i = 0; i < 3; ++i) {
    const FrameTracks t = tracker.Process(MakeFrame(black, i, 0.5));
    EXPECT_TRUE(t.blank);
    EXPECT_TRUE(t.points.empty());
    EXPECT_EQ(t.quality, 0);
    EXPECT_EQ(t.shot, 0);
  }
  // Content after leading black is still shot 0 (nothing to separate from).
  const FrameTracks t = tracker.Process(MakeFrame(Shifted(a, 0, 0, kDecoded), 3, 0.5));
  EXPECT_FALSE(t.blank);
  EXPECT_EQ(t.shot, 0);
  EXPECT_EQ(t.boundary, ShotBoundary::kNone);
  EXPECT_GT(t.points.size(), 250u);
  // A flat grey frame is blank too.
  const FrameTracks g =
      tracker.Process(MakeFrame(cv::Mat(kDecoded, CV_8UC3, cv::Scalar(128, 128, 128)), 4, 0.5));
  EXPECT_TRUE(g.blank);
  EXPECT_TRUE(g.points.empty());
}

TEST(FeatureTrackerTest, FadeThroughBlackSplitsShots) {
  const cv::Mat a = NoiseTexture({1000, 800}, 10, {0.5, 0.0, -0.5});
  const cv::Mat b = NoiseTexture({1000, 800}, 11, {-0.5, 0.0, 0.5});
  FeatureTracker tracker(SmallOptions());
  // 0-9 A, 10-19 fade out, 20-22 black, 23-32 fade in B, 33-40 B.
  std::vector<FrameTracks> out;
  for (int i = 0; i <= 40; ++i) {
    double gain = 1;
    const cv::Mat* tex = &a;
    if (i >= 10 && i < 20) gain = 1 - (i - 9) / 10.0;
    if (i >= 20 && i < 23) gain = 0;
    if (i >= 23) tex = &b;
    if (i >= 23 && i < 33) gain = (i - 22) / 10.0;
    cv::Mat img = Shifted(*tex, 1.0 * i, 0, kDecoded);
    img.convertTo(img, -1, gain, 0);
    out.push_back(tracker.Process(MakeFrame(img, i, 0.5)));
  }
  int fades = 0, cuts = 0;
  for (const auto& t : out) {
    fades += t.boundary == ShotBoundary::kFade;
    cuts += t.boundary == ShotBoundary::kCut;
  }
  EXPECT_EQ(cuts, 0);
  EXPECT_EQ(fades, 1);
  for (int i = 20; i < 23; ++i) EXPECT_TRUE(out[i].blank) << i;
  for (int i = 0; i < 10; ++i) EXPECT_EQ(out[i].shot, 0);
  for (int i = 33; i <= 40; ++i) EXPECT_EQ(out[i].shot, 1);
  // Mid-fade frames are either blank or low quality.
  for (int i = 15; i < 28; ++i)
    EXPECT_TRUE(out[i].blank || out[i].quality <= 0.25) << "frame " << i;
  EXPECT_GT(out[40].quality, 0.8);
}

TEST(FeatureTrackerTest, FadeThroughBlackOnTheSameSceneKeepsTheShot) {
  // A panning camera fades to black and back on the same scene: the frame
  // after the black re-links to the last good frame before it (descriptor
  // matching), so there is no boundary and track ids carry on.
  const cv::Mat a = NoiseTexture({1000, 800}, 14, {0.5, 0.0, -0.5});
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  for (int i = 0; i <= 40; ++i) {
    double gain = 1;
    if (i >= 10 && i < 20) gain = 1 - (i - 9) / 10.0;
    if (i >= 20 && i < 23) gain = 0;
    if (i >= 23 && i < 33) gain = (i - 22) / 10.0;
    cv::Mat img = Shifted(a, 3.0 * i, 0, kDecoded);
    img.convertTo(img, -1, gain, 0);
    out.push_back(tracker.Process(MakeFrame(img, i, 0.5)));
  }
  for (int i = 20; i < 23; ++i) EXPECT_TRUE(out[i].blank) << i;
  for (const auto& t : out) {
    EXPECT_EQ(t.shot, 0) << t.index;
    EXPECT_NE(t.boundary, ShotBoundary::kFade) << t.index;
  }
  // Some ids seen before the black are seen again after it.
  std::set<long> before;
  for (int i = 0; i < 20; ++i)
    for (const auto& p : out[i].points) before.insert(p.track_id);
  int first_after = 23;  // the first frame bright enough not to be blank
  while (first_after < 40 && out[first_after].blank) ++first_after;
  int shared = 0;
  for (const auto& p : out[first_after].points) shared += before.count(p.track_id);
  EXPECT_GE(shared, 20) << "frame " << first_after;
}

TEST(FeatureTrackerTest, DissolveIsAGradualBoundary) {
  const cv::Mat a = NoiseTexture({1000, 800}, 12, {0.8, 0.0, -0.6});
  const cv::Mat b = NoiseTexture({1000, 800}, 13, {-0.6, 0.2, 0.8});
  FeatureTracker tracker(SmallOptions());
  std::vector<FrameTracks> out;
  for (int i = 0; i < 36; ++i) {
    const double w = std::clamp((i - 10) / 12.0, 0.0, 1.0);  // 10..22 dissolve
    cv::Mat img;
    cv::addWeighted(Shifted(a, 1.0 * i, 0, kDecoded), 1 - w, Shifted(b, 0, 1.0 * i, kDecoded), w, 0,
                    img);
    out.push_back(tracker.Process(MakeFrame(img, i, 0.5)));
  }
  int fades = 0, cuts = 0, first_fade = -1;
  for (const auto& t : out) {
    if (t.boundary == ShotBoundary::kFade && first_fade < 0) first_fade = t.index;
    fades += t.boundary == ShotBoundary::kFade;
    cuts += t.boundary == ShotBoundary::kCut;
  }
  EXPECT_EQ(cuts, 0);
  EXPECT_EQ(fades, 1);
  EXPECT_GE(first_fade, 12);
  EXPECT_LE(first_fade, 26);
  EXPECT_EQ(out.back().shot, 1);
}

// A dissolve between two views of one set (the same colours: the
// histograms before and after are close) during a pan: KLT follows the
// fading picture, so only the picture moved by the tracked motion shows
// that the run ended on another view. One gradual boundary.
TEST(FeatureTrackerTest, DissolveBetweenLookAlikeViewsDuringAPanIsABoundary) {
  const cv::Mat scene = NoiseTexture({3200, 800}, 26);
  FeatureTracker tracker(SmallOptions());
  ShotDetector histograms_only;
  int histogram_boundaries = 0;
  std::vector<FrameTracks> out;
  for (int i = 0; i < 44; ++i) {
    // Still for 6 frames, then a pan at 6 px/frame; the dissolve 16..22.
    const double w = std::clamp((i - 16) / 6.0, 0.0, 1.0);
    const double x = 6.0 * std::max(0, i - 6);
    const cv::Mat a = Shifted(scene, -x, 0, kDecoded, {200, 100});
    const cv::Mat b = Shifted(scene, -x, 0, kDecoded, {1800, 100});  // no overlap
    cv::Mat img;
    cv::addWeighted(a, 1 - w, b, w, 0, img);
    const Frame frame = MakeFrame(img, i, 0.5);
    histogram_boundaries += histograms_only.Update(frame).boundary != ShotBoundary::kNone;
    out.push_back(tracker.Process(frame));
  }
  EXPECT_EQ(histogram_boundaries, 0) << "the histograms alone must not see it";
  int fades = 0, cuts = 0, first_fade = -1;
  for (const auto& t : out) {
    if (t.boundary == ShotBoundary::kFade && first_fade < 0) first_fade = t.index;
    fades += t.boundary == ShotBoundary::kFade;
    cuts += t.boundary == ShotBoundary::kCut;
  }
  EXPECT_EQ(cuts, 0);
  EXPECT_EQ(fades, 1);
  EXPECT_GE(first_fade, 18);
  EXPECT_LE(first_fade, 28);
  EXPECT_EQ(out.back().shot, 1);
}

// A tilt from the floor to the ceiling changes the colours on screen
// gradually, like a dissolve: the histogram test alone would split the shot
// there. KLT follows the content all the way, so it stays one shot.
TEST(FeatureTrackerTest, PanAcrossChangingColoursIsNotADissolve) {
  // Two differently tinted textures side by side, blended over 200 px.
  const cv::Mat wide = BlendedAcross(NoiseTexture({2400, 800}, 21, {-0.9, -0.8, -0.6}),
                                     NoiseTexture({2400, 800}, 22, {0.6, 0.9, 0.9}), 1100, 200);
  FeatureTracker tracker(SmallOptions());
  ShotDetector histograms_only;
  int histogram_fades = 0;
  std::vector<FrameTracks> out;
  for (int i = 0; i < 60; ++i) {
    // Still for 10 frames, an eased 960 px (decoded) move over 40 frames, still.
    const double t = std::clamp((i - 10) / 40.0, 0.0, 1.0);
    const double x = 960.0 * (0.5 - 0.5 * std::cos(M_PI * t));
    const Frame frame = MakeFrame(Shifted(wide, -x, 0, kDecoded), i, 0.5);
    histogram_fades += histograms_only.Update(frame).boundary == ShotBoundary::kFade;
    out.push_back(tracker.Process(frame));
  }
  int boundaries = 0, transitions = 0;
  for (const auto& t : out) {
    boundaries += t.boundary == ShotBoundary::kFade || t.boundary == ShotBoundary::kCut;
    transitions += t.transition;
  }
  ASSERT_GT(histogram_fades, 0) << "the colour change must look like a dissolve to the histograms";
  EXPECT_GT(transitions, 0);
  EXPECT_EQ(boundaries, 0);
  EXPECT_EQ(out.back().shot, 0);
  EXPECT_GT(out.back().points.size(), 100u) << "tracking continues through the pan";
}

TEST(FeatureTrackerTest, RejectsBadInputAndOptions) {
  FeatureTracker tracker;
  Frame empty;
  EXPECT_THROW(tracker.Process(empty), Error);
  TrackerOptions o;
  o.klt_window = 20;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.fb_threshold_px = 0;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.max_tracks = 0;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.klt_coarse_iterations = 0;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.klt_coarse_step_px = 0;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o.klt_coarse_step_px = std::nan("");
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.klt_anchor_frames = -1;
  EXPECT_THROW(FeatureTracker{o}, UsageError);
  o = {};
  o.klt_anchor_min_px = std::nan("");
  EXPECT_THROW(FeatureTracker{o}, UsageError);
}

}  // namespace
}  // namespace hapcine
