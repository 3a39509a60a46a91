#pragma once
// Links the tracks of one frame to another across motion KLT cannot bridge
// (stills, low frame rates, crash zooms, whip pans, fast orbits, large
// rolls): SIFT keypoints and descriptors (rotation- and scale-invariant) in
// both frames, Lowe's ratio test and a cross check, then geometric
// verification with the model that holds, chosen by GRIC: a homography
// (a rotation, a plane, a far scene) unless parallax pays for the
// fundamental matrix (an orbit, a traveling). Track ids continue two ways:
//   - a keyframe track point that is itself one of the keyframe's SIFT
//     keypoints follows its verified match;
//   - the other keyframe tracks (KLT corners) follow a guided KLT: the
//     current frame is warped into the keyframe's geometry by the homography
//     fitted to the verified matches, so a 60 degree roll or a 2x zoom
//     leaves KLT a small residual motion; the answer is mapped back,
//     checked forward-backward and against the verified model.
// Algorithms print nothing.

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

#include "extract/pyramid_lk.h"

namespace hapcine {

// A frame as the linker sees it: its image, SIFT keypoints and descriptors,
// and its track points (with the keypoint each one sits on, if any).
struct DescribedFrame {
  cv::Mat gray;  // shared, not copied
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;                 // one row per keypoint (CV_32F)
  std::vector<cv::Point2f> points;     // the frame's track points
  std::vector<long> ids;               // their track ids
  std::vector<int> point_of_keypoint;  // per keypoint: index into points, or -1
  bool empty() const { return gray.empty(); }
};

// Descriptor matches as index pairs into two keypoint lists, and their points.
struct DescriptorMatches {
  std::vector<int> key, cur;
  std::vector<cv::Point2f> key_pts, cur_pts;
};

enum class LinkModel { kNone, kHomography, kFundamental };

struct LinkResult {
  LinkModel model = LinkModel::kNone;
  std::vector<cv::Point2f> points;      // current frame (working px), continuing ids
  std::vector<long> ids;
  std::vector<cv::Point2f> key_points;  // the same tracks in the keyframe
  // Per current keypoint: the index into `points` it carries, or -1.
  std::vector<int> point_of_keypoint;
  cv::Mat current_from_key;  // homography: the model, or the warp approximating it
  cv::Mat fundamental;       // the verified model when kFundamental (cur^T F key = 0)
  int verified_matches = 0;  // descriptor matches the model accepts
  double median_motion_px = 0;  // median displacement of the verified matches
  bool ok() const { return model != LinkModel::kNone; }
  bool guided = false;  // found by guided matching
};

struct DescriptorLinkerOptions {
  int max_features = 1200;    // SIFT keypoints per frame (strongest)
  // SIFT's DoG contrast threshold (OpenCV's default 0.04): lower, so that
  // low-texture pictures (a matte object on black, a synthetic set) still
  // give a few hundred keypoints; textured ones are capped by max_features,
  // which keeps the strongest anyway.
  double contrast_threshold = 0.01;
  // Guided matching (when plain matching finds too few): only keyframe
  // keypoints within this distance (px) of the epipolar line (or the
  // transfer) the predicted motion gives are candidates, and the ratio test
  // runs among them.
  double guided_px = 6.0;
  double guided_ratio = 0.9;  // the ratio test there, against the whole keyframe
  int min_verified = 15;      // fewer verified matches: no link
  double ratio = 0.8;         // Lowe's ratio test
  // RANSAC thresholds, working px: SIFT keypoints are located to a few
  // tenths of a pixel; point-to-epipolar-line distance for F, transfer
  // error for the homography.
  double fundamental_px = 1.5;
  double homography_px = 3.0;
  // Localisation noise of a matched keypoint (px), for GRIC's choice
  // between the homography and the fundamental matrix.
  double sigma_px = 1.0;
  PyramidLkOptions lk;        // guided KLT
  double fb_threshold_px = 0.5;
};

class DescriptorLinker {
 public:
  explicit DescriptorLinker(const DescriptorLinkerOptions& options = {});
  const DescriptorLinkerOptions& options() const { return options_; }
  // SIFT keypoints and descriptors of frame->gray (the strongest
  // max_features); point_of_keypoint all -1.
  void Describe(DescribedFrame* frame) const;
  // Links `current` (described) to `key` (described, with its track
  // points). Empty result (model kNone) when fewer than min_verified
  // matches survive.
  // `predicted`: the motion expected from `key` to `current` (the last
  // link's, for a constant step: an orbit, stills from a turntable), used
  // for guided matching when plain matching verifies too few; may be none.
  LinkResult Link(const DescribedFrame& key, const DescribedFrame& current,
                  const LinkResult* predicted = nullptr) const;
  // Whether a track from `key_point` to `point` agrees with the verified
  // model (epipolar distance or homography transfer within its threshold).
  bool Agrees(const LinkResult& link, const cv::Point2f& key_point, const cv::Point2f& point) const;

 private:
  LinkResult Verify(const DescribedFrame& key, const DescribedFrame& current, const DescriptorMatches& m) const;
  bool GricPrefersHomography(const cv::Mat& h, const cv::Mat& f, const DescriptorMatches& m) const;
  void GuidedKlt(const DescribedFrame& key, const DescribedFrame& current, LinkResult* result) const;
  DescriptorLinkerOptions options_;
  cv::Ptr<cv::SIFT> sift_;
};

}  // namespace hapcine
