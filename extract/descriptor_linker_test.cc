#include "extract/descriptor_linker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "extract/test_frames.h"

namespace hapcine {
namespace {

using testing::NoiseTexture;

const cv::Size kSize(640, 480);

cv::Mat Gray(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

// The view of `texture` under image_from_texture (3x3), gray.
cv::Mat View(const cv::Mat& texture, const cv::Matx33d& image_from_texture) {
  cv::Mat out;
  cv::warpPerspective(texture, out, cv::Mat(image_from_texture), kSize, cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return Gray(out);
}

cv::Matx33d Translation(double dx, double dy) { return {1, 0, dx, 0, 1, dy, 0, 0, 1}; }

// Rotation by `deg` and scaling by `scale` about the image centre.
cv::Matx33d AboutCentre(double deg, double scale) {
  const cv::Mat a = cv::getRotationMatrix2D({(kSize.width - 1) / 2.0f, (kSize.height - 1) / 2.0f}, deg, scale);
  cv::Matx33d m = cv::Matx33d::eye();
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = a.at<double>(r, c);
  return m;
}

cv::Point2f Apply(const cv::Matx33d& h, const cv::Point2f& p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1);
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

// The keyframe's tracks: KLT-style corners (ids from 0), which only the
// guided KLT can carry, and its SIFT keypoints (ids from 100000), which the
// descriptor matches carry.
DescribedFrame Keyframe(const DescriptorLinker& linker, const cv::Mat& gray) {
  DescribedFrame key;
  key.gray = gray;
  linker.Describe(&key);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(gray, corners, 200, 0.01, 8);
  for (size_t i = 0; i < corners.size(); ++i) {
    key.points.push_back(corners[i]);
    key.ids.push_back(static_cast<long>(i));
  }
  for (size_t k = 0; k < key.keypoints.size(); k += 2) {
    key.point_of_keypoint[k] = static_cast<int>(key.points.size());
    key.points.push_back(key.keypoints[k].pt);
    key.ids.push_back(100000 + static_cast<long>(k));
  }
  return key;
}

struct Carried {
  int off = 0;
};

// Every carried track against the true motion current_from_key.
Carried Check(const LinkResult& r, const cv::Matx33d& current_from_key, double tol_px) {
  Carried c;
  for (size_t i = 0; i < r.points.size(); ++i) {
    if (cv::norm(Apply(current_from_key, r.key_points[i]) - r.points[i]) > tol_px) ++c.off;
  }
  return c;
}

class DescriptorLinkerMotion : public ::testing::TestWithParam<std::pair<double, double>> {};

// A 60 degree roll and a 2x zoom (KLT from zero motion loses both) are
// linked with the homography, and the tracks carried by descriptors and by
// the guided KLT land on the true positions.
TEST_P(DescriptorLinkerMotion, RollAndZoomAreLinkedOntoTheTruePositions) {
  const auto [deg, scale] = GetParam();
  const cv::Mat texture = NoiseTexture({1400, 1200}, 11);
  const cv::Matx33d key_from_texture = Translation(-380, -360);
  const cv::Matx33d current_from_key = AboutCentre(deg, scale);
  DescriptorLinker linker;
  const DescribedFrame key = Keyframe(linker, View(texture, key_from_texture));
  DescribedFrame cur;
  cur.gray = View(texture, current_from_key * key_from_texture);
  linker.Describe(&cur);
  const LinkResult r = linker.Link(key, cur);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.model, LinkModel::kHomography);
  const Carried c = Check(r, current_from_key, 1.0);
  EXPECT_LE(c.off, 2) << "of " << r.points.size();
  EXPECT_GT(r.median_motion_px, 17);  // beyond a KLT window
  // Carried by a descriptor match: the current keypoint names its track,
  // a keypoint track of the keyframe; the others by the guided KLT.
  int matched = 0;
  for (int p : r.point_of_keypoint)
    if (p >= 0) {
      ++matched;
      EXPECT_GE(r.ids[p], 100000);
    }
  EXPECT_GE(matched, 40);
  EXPECT_GE(static_cast<int>(r.points.size()) - matched, 40);  // guided KLT
}

INSTANTIATE_TEST_SUITE_P(Motions, DescriptorLinkerMotion,
                         ::testing::Values(std::make_pair(60.0, 1.0), std::make_pair(0.0, 2.0),
                                           std::make_pair(-35.0, 0.6)));

// Two planes moving by different amounts (parallax along x): one
// homography explains only one plane, the fundamental matrix both, so the
// link is kFundamental and carries tracks on both planes.
TEST(DescriptorLinkerTest, ParallaxIsVerifiedByTheFundamentalMatrix) {
  const cv::Mat near = Gray(NoiseTexture({1200, 600}, 21)), far = Gray(NoiseTexture({1200, 600}, 22));
  auto view = [&](double near_dx, double far_dx) {
    cv::Mat out(kSize, CV_8U);
    cv::Mat a, b;
    cv::warpAffine(near, a, cv::Mat(cv::Matx23d(1, 0, near_dx - 300, 0, 1, -50)), kSize);
    cv::warpAffine(far, b, cv::Mat(cv::Matx23d(1, 0, far_dx - 300, 0, 1, -50)), kSize);
    a.rowRange(0, 240).copyTo(out.rowRange(0, 240));
    b.rowRange(240, 480).copyTo(out.rowRange(240, 480));
    return out;
  };
  DescriptorLinker linker;
  DescribedFrame key = Keyframe(linker, view(0, 0));
  DescribedFrame cur;
  cur.gray = view(-80, -30);
  linker.Describe(&cur);
  const LinkResult r = linker.Link(key, cur);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.model, LinkModel::kFundamental);
  int top = 0, bottom = 0, off = 0;
  for (size_t i = 0; i < r.points.size(); ++i) {
    const cv::Point2f d = r.points[i] - r.key_points[i];
    const bool is_top = r.key_points[i].y < 230, is_bottom = r.key_points[i].y > 250;
    top += is_top;
    bottom += is_bottom;
    if ((is_top && std::abs(d.x + 80) > 1) || (is_bottom && std::abs(d.x + 30) > 1) || std::abs(d.y) > 1) ++off;
  }
  EXPECT_GE(top, 20);
  EXPECT_GE(bottom, 20);
  EXPECT_LE(off, 3);
}

// Two unrelated pictures: no link (the tracker then splits the shot).
TEST(DescriptorLinkerTest, UnrelatedPicturesAreNotLinked) {
  DescriptorLinker linker;
  const DescribedFrame key = Keyframe(linker, Gray(NoiseTexture(kSize, 31)));
  DescribedFrame cur;
  cur.gray = Gray(NoiseTexture(kSize, 32));
  linker.Describe(&cur);
  EXPECT_FALSE(linker.Link(key, cur).ok());
  DescribedFrame empty;
  empty.gray = cv::Mat(kSize, CV_8U, cv::Scalar(128));  // flat: no keypoints
  linker.Describe(&empty);
  EXPECT_TRUE(empty.keypoints.empty());
  EXPECT_FALSE(linker.Link(key, empty).ok());
  EXPECT_FALSE(linker.Link(empty, cur).ok());
}

}  // namespace
}  // namespace hapcine
