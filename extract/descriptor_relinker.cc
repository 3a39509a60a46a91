#include "extract/descriptor_relinker.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <unordered_map>

#include "extract/grid_detector.h"
#include "extract/keep_tracks.h"

namespace hapcine {
namespace {

constexpr float kPatchSize = 31;

std::vector<cv::KeyPoint> Upright(const std::vector<cv::Point2f>& points) {
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    keypoints.emplace_back(points[i], kPatchSize, 0.f, 0.f, 0, static_cast<int>(i));
  return keypoints;
}

}  // namespace

DescriptorRelinker::DescriptorRelinker(int min_matches)
    : min_matches_(min_matches),
      // One level, 31-px patches: descriptors only, detection is ours.
      orb_(cv::ORB::create(500, 1.2f, 1, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20)) {}

void DescriptorRelinker::SetKeyframe(const cv::Mat& gray, const std::vector<cv::Point2f>& points,
                                     const std::vector<long>& ids) {
  key_gray_ = gray;
  key_points_ = points;
  key_ids_ = ids;
  key_described_ = false;
  key_keypoints_.clear();
  key_descriptors_.release();
}

void DescriptorRelinker::Clear() { SetKeyframe(cv::Mat(), {}, {}); }

RelinkResult DescriptorRelinker::Relink(const cv::Mat& gray, int max_features) {
  RelinkResult result;
  if (key_gray_.empty() || key_points_.size() < static_cast<size_t>(min_matches_)) return result;
  if (!key_described_) {
    key_keypoints_ = Upright(key_points_);
    orb_->compute(key_gray_, key_keypoints_, key_descriptors_);
    key_described_ = true;
  }
  if (key_descriptors_.rows < min_matches_) return result;

  GridDetectorOptions detect;
  detect.grid_cols = 8;
  detect.grid_rows = 6;
  detect.per_cell = (max_features + 47) / 48;
  detect.min_distance_px = 6;
  std::vector<cv::Point2f> corners;
  DetectGridCorners(gray, {}, max_features, detect, &corners);
  std::vector<cv::KeyPoint> cur_keypoints = Upright(corners);
  cv::Mat cur_descriptors;
  orb_->compute(gray, cur_keypoints, cur_descriptors);
  if (cur_descriptors.rows < min_matches_) return result;

  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward;
  std::vector<cv::DMatch> backward;
  matcher.knnMatch(cur_descriptors, key_descriptors_, forward, 2);
  matcher.match(key_descriptors_, cur_descriptors, backward);
  std::vector<cv::Point2f> key_pts, cur_pts;
  std::vector<int> key_index;
  for (const auto& m : forward) {
    if (m.size() < 2 || m[0].distance >= 0.8f * m[1].distance) continue;  // ratio test
    if (backward[m[0].trainIdx].trainIdx != m[0].queryIdx) continue;      // cross check
    cur_pts.push_back(cur_keypoints[m[0].queryIdx].pt);
    key_pts.push_back(key_keypoints_[m[0].trainIdx].pt);
    key_index.push_back(key_keypoints_[m[0].trainIdx].class_id);
  }
  if (static_cast<int>(cur_pts.size()) < min_matches_) return result;
  std::vector<unsigned char> inlier;
  const cv::Mat h = cv::findHomography(key_pts, cur_pts, cv::RANSAC, 3.0, inlier, 2000, 0.995);
  if (h.empty()) return result;
  for (size_t i = 0; i < cur_pts.size(); ++i) {
    if (!inlier[i]) continue;
    result.points.push_back(cur_pts[i]);
    result.ids.push_back(key_ids_[key_index[i]]);
    result.key_points.push_back(key_points_[key_index[i]]);
  }
  if (static_cast<int>(result.points.size()) < min_matches_) return {};
  result.current_from_key = h;
  return result;
}

void DescriptorRelinker::KeepConsistent(const cv::Mat& current_from_key, double tol_px,
                                        std::vector<cv::Point2f>* points,
                                        std::vector<long>* ids) const {
  std::unordered_map<long, cv::Point2f> key_by_id;
  for (size_t i = 0; i < key_ids_.size(); ++i) key_by_id[key_ids_[i]] = key_points_[i];
  const cv::Matx33d h(current_from_key);
  KeepTracksIf(points, ids, [&](size_t i) {
    auto it = key_by_id.find((*ids)[i]);
    if (it == key_by_id.end()) return false;
    const cv::Vec3d q = h * cv::Vec3d(it->second.x, it->second.y, 1.0);
    if (!(std::abs(q[2]) > 1e-12)) return false;
    const double dx = q[0] / q[2] - (*points)[i].x, dy = q[1] / q[2] - (*points)[i].y;
    return dx * dx + dy * dy <= tol_px * tol_px;
  });
}

}  // namespace hapcine
