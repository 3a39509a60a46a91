#pragma once
// Re-links tracks across a tracking collapse (whip pan, motion blur, a frame
// jump) by ORB descriptor matching between the last good frame ("keyframe")
// and the current frame.
//
// Only the keyframe is kept: its gray image (shared, not copied), its track
// points and ids; descriptors are computed lazily, the first time a recovery
// is attempted against it. Descriptors are upright (angle 0, one scale): the
// keyframe's descriptors sit on its KLT track points, the current frame's on
// fresh Shi-Tomasi corners. Matches must pass Lowe's ratio test (0.8), a
// cross check (mutual best), and a RANSAC homography (3 working px).

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

namespace hapcine {

struct RelinkResult {
  std::vector<cv::Point2f> points;      // positions in the current frame (working px)
  std::vector<long> ids;                // keyframe track ids they continue
  std::vector<cv::Point2f> key_points;  // the same tracks in the keyframe
  cv::Mat current_from_key;             // RANSAC homography (3x3), empty on failure
};

class DescriptorRelinker {
 public:
  explicit DescriptorRelinker(int min_matches = 15);
  // Remembers a good frame. `gray` is shared (cv::Mat refcount), not copied.
  void SetKeyframe(const cv::Mat& gray, const std::vector<cv::Point2f>& points,
                   const std::vector<long>& ids);
  void Clear();
  bool has_keyframe() const { return !key_gray_.empty(); }
  const cv::Mat& key_gray() const { return key_gray_; }
  const std::vector<cv::Point2f>& key_points() const { return key_points_; }
  const std::vector<long>& key_ids() const { return key_ids_; }
  // Matches `gray` against the keyframe. Empty result when fewer than
  // min_matches survive the checks.
  RelinkResult Relink(const cv::Mat& gray, int max_features);
  // Keeps only the points whose id is in the keyframe and that sit within
  // tol_px of where current_from_key maps the keyframe point: after a
  // collapse, KLT "survivors" that disagree with the recovered motion are
  // false (LK converged to a look-alike patch both ways).
  void KeepConsistent(const cv::Mat& current_from_key, double tol_px,
                      std::vector<cv::Point2f>* points, std::vector<long>* ids) const;

 private:
  int min_matches_;
  cv::Ptr<cv::ORB> orb_;
  cv::Mat key_gray_;
  std::vector<cv::Point2f> key_points_;
  std::vector<long> key_ids_;
  bool key_described_ = false;
  std::vector<cv::KeyPoint> key_keypoints_;  // after ORB's border filter
  cv::Mat key_descriptors_;
};

}  // namespace hapcine
