#include "extract/descriptor_linker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <unordered_set>

#include "core/statistics.h"

namespace hapcine {
namespace {


// Lowe's ratio test on the two nearest keyframe descriptors of each current
// one, and a cross check (the keyframe descriptor's nearest is this one).
DescriptorMatches MatchDescriptors(const DescribedFrame& key, const DescribedFrame& cur, double ratio) {
  DescriptorMatches m;
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward;
  std::vector<cv::DMatch> backward;
  matcher.knnMatch(cur.descriptors, key.descriptors, forward, 2);
  matcher.match(key.descriptors, cur.descriptors, backward);
  for (const auto& f : forward) {
    if (f.size() < 2 || f[0].distance >= ratio * f[1].distance) continue;
    if (backward[f[0].trainIdx].trainIdx != f[0].queryIdx) continue;
    m.cur.push_back(f[0].queryIdx);
    m.key.push_back(f[0].trainIdx);
    m.cur_pts.push_back(cur.keypoints[f[0].queryIdx].pt);
    m.key_pts.push_back(key.keypoints[f[0].trainIdx].pt);
  }
  return m;
}

int Count(const std::vector<unsigned char>& mask) {
  return static_cast<int>(std::count_if(mask.begin(), mask.end(), [](unsigned char b) { return b != 0; }));
}

// Distance of `cur` from the epipolar line of `key` (cur^T F key = 0), px.
double EpipolarDistance(const cv::Matx33d& f, const cv::Point2f& key, const cv::Point2f& cur) {
  const cv::Vec3d line = f * cv::Vec3d(key.x, key.y, 1.0);
  const double norm = std::hypot(line[0], line[1]);
  if (!(norm > 1e-12)) return std::numeric_limits<double>::infinity();
  return std::abs(line[0] * cur.x + line[1] * cur.y + line[2]) / norm;
}

cv::Point2f Apply(const cv::Matx33d& h, const cv::Point2f& p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
  if (!(std::abs(q[2]) > 1e-12)) return {std::numeric_limits<float>::quiet_NaN(), 0.f};
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

// Candidates restricted by the predicted motion: each current keypoint is
// compared only with the keyframe keypoints the prediction puts near it
// (`near`), and its best one there must pass a relaxed ratio test against
// the nearest *other* descriptor of the whole keyframe (`global_ratio`):
// the restriction alone would let any descriptor win among a few
// candidates, and two unrelated pictures would verify the prediction they
// were matched by. Each keyframe keypoint keeps its best match only.
template <typename Near>
DescriptorMatches GuidedMatches(const DescribedFrame& key, const DescribedFrame& cur, double global_ratio,
                                Near near) {
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> nearest;
  matcher.knnMatch(cur.descriptors, key.descriptors, nearest, 2);
  std::vector<int> best_cur(key.keypoints.size(), -1);
  std::vector<float> best_cur_distance(key.keypoints.size(), std::numeric_limits<float>::infinity());
  for (size_t c = 0; c < cur.keypoints.size(); ++c) {
    float d1 = std::numeric_limits<float>::infinity(), d2 = d1;
    int k1 = -1;
    for (size_t k = 0; k < key.keypoints.size(); ++k) {
      if (!near(key.keypoints[k].pt, cur.keypoints[c].pt)) continue;
      const float d = static_cast<float>(cv::norm(cur.descriptors.row(static_cast<int>(c)),
                                                  key.descriptors.row(static_cast<int>(k)), cv::NORM_L2));
      if (d < d1) {
        d2 = d1;
        d1 = d;
        k1 = static_cast<int>(k);
      } else if (d < d2) {
        d2 = d;
      }
    }
    if (k1 < 0 || d1 >= best_cur_distance[k1]) continue;
    const auto& n = nearest[c];
    const float other = n.empty() ? d2 : (n[0].trainIdx != k1 ? n[0].distance : n.size() > 1 ? n[1].distance : d2);
    if (!(d1 < global_ratio * other)) continue;
    best_cur[k1] = static_cast<int>(c);
    best_cur_distance[k1] = d1;
  }
  DescriptorMatches m;
  for (size_t k = 0; k < best_cur.size(); ++k) {
    if (best_cur[k] < 0) continue;
    m.key.push_back(static_cast<int>(k));
    m.cur.push_back(best_cur[k]);
    m.key_pts.push_back(key.keypoints[k].pt);
    m.cur_pts.push_back(cur.keypoints[best_cur[k]].pt);
  }
  return m;
}

}  // namespace

DescriptorLinker::DescriptorLinker(const DescriptorLinkerOptions& options)
    : options_(options), sift_(cv::SIFT::create(options.max_features, 3, options.contrast_threshold)) {}

void DescriptorLinker::Describe(DescribedFrame* frame) const {
  frame->keypoints.clear();
  frame->descriptors.release();
  sift_->detectAndCompute(frame->gray, cv::noArray(), frame->keypoints, frame->descriptors);
  frame->point_of_keypoint.assign(frame->keypoints.size(), -1);
}

LinkResult DescriptorLinker::Link(const DescribedFrame& key, const DescribedFrame& current,
                                  const LinkResult* predicted) const {
  if (key.descriptors.rows < options_.min_verified || current.descriptors.rows < options_.min_verified)
    return {};
  LinkResult result = Verify(key, current, MatchDescriptors(key, current, options_.ratio));
  if (!result.ok() && predicted && predicted->ok()) {
    const double r = options_.guided_px;
    const LinkResult& p = *predicted;
    const DescriptorMatches guided = GuidedMatches(key, current, options_.guided_ratio, [&](const cv::Point2f& a, const cv::Point2f& b) {
      if (p.model == LinkModel::kFundamental) return EpipolarDistance(cv::Matx33d(p.fundamental), a, b) <= r;
      return cv::norm(Apply(cv::Matx33d(p.current_from_key), a) - b) <= r;
    });
    result = Verify(key, current, guided);
    result.guided = result.ok();
  }
  if (result.ok() && !result.current_from_key.empty()) GuidedKlt(key, current, &result);
  return result;
}

// Torr's GRIC over all the matches, sum_i min(e_i^2 / sigma^2, 2 (r - d)) +
// n d ln r + k ln(r n), r = 4: a homography (d = 2, k = 8; e^2 half the
// squared transfer error) against a fundamental matrix (d = 3, k = 7; e
// the distance from the epipolar line). A fundamental matrix also fits
// every match of a plane or a rotation, and on a plane RANSAC finds one
// that takes in wrong matches along their epipolar lines as well; the
// homography wins unless parallax pays for the extra dimension.
bool DescriptorLinker::GricPrefersHomography(const cv::Mat& h, const cv::Mat& f, const DescriptorMatches& m) const {
  const double sigma2 = options_.sigma_px * options_.sigma_px, r = 4;
  const double n = static_cast<double>(m.cur.size());
  const cv::Matx33d hm(h), fm(f);
  double gric_h = n * 2 * std::log(r) + 8 * std::log(r * n), gric_f = n * 3 * std::log(r) + 7 * std::log(r * n);
  for (size_t i = 0; i < m.cur.size(); ++i) {
    const cv::Point2f t = Apply(hm, m.key_pts[i]) - m.cur_pts[i];
    const double e_h = 0.5 * (t.x * t.x + t.y * t.y), e_f = std::pow(EpipolarDistance(fm, m.key_pts[i], m.cur_pts[i]), 2);
    gric_h += std::min(e_h / sigma2, 2 * (r - 2));
    gric_f += std::min(e_f / sigma2, 2 * (r - 3));
  }
  return gric_h <= gric_f;
}

// The model the matches verify (homography or fundamental matrix), and the
// keyframe tracks that matched keypoints carry.
LinkResult DescriptorLinker::Verify(const DescribedFrame& key, const DescribedFrame& current, const DescriptorMatches& m) const {
  LinkResult result;
  if (m.cur.size() < static_cast<size_t>(options_.min_verified)) return result;
  std::vector<unsigned char> in_f, in_h;
  const cv::Mat f = cv::findFundamentalMat(m.key_pts, m.cur_pts, cv::FM_RANSAC, options_.fundamental_px,
                                           0.999, 5000, in_f);
  const cv::Mat h = cv::findHomography(m.key_pts, m.cur_pts, cv::RANSAC, options_.homography_px, in_h, 5000, 0.999);
  const int n_f = f.rows == 3 ? Count(in_f) : 0, n_h = h.empty() ? 0 : Count(in_h);
  const std::vector<unsigned char>* inlier = nullptr;
  if (n_h >= options_.min_verified && (n_f < options_.min_verified || GricPrefersHomography(h, f, m))) {
    result.model = LinkModel::kHomography;
    result.current_from_key = h;
    inlier = &in_h;
  } else if (n_f >= options_.min_verified) {
    result.model = LinkModel::kFundamental;
    result.fundamental = f;
    inlier = &in_f;
    // The warp the guided KLT starts from: a homography through the
    // verified matches with a loose threshold (the dominant depth).
    std::vector<cv::Point2f> kp, cp;
    for (size_t i = 0; i < m.cur.size(); ++i)
      if (in_f[i]) {
        kp.push_back(m.key_pts[i]);
        cp.push_back(m.cur_pts[i]);
      }
    result.current_from_key = cv::findHomography(kp, cp, cv::RANSAC, 4 * options_.homography_px);
  } else {
    return result;
  }
  result.point_of_keypoint.assign(current.keypoints.size(), -1);
  std::vector<float> motion;
  for (size_t i = 0; i < m.cur.size(); ++i) {
    if (!(*inlier)[i]) continue;
    ++result.verified_matches;
    const cv::Point2f d = m.cur_pts[i] - m.key_pts[i];
    motion.push_back(std::hypot(d.x, d.y));
    const int point = key.point_of_keypoint.empty() ? -1 : key.point_of_keypoint[m.key[i]];
    if (point < 0) continue;
    result.point_of_keypoint[m.cur[i]] = static_cast<int>(result.points.size());
    result.points.push_back(m.cur_pts[i]);
    result.ids.push_back(key.ids[point]);
    result.key_points.push_back(key.points[point]);
  }
  result.median_motion_px = Quantile(std::move(motion), 0.5);
  return result;
}

// KLT of the keyframe tracks the descriptors did not carry, against the
// current frame warped into the keyframe's geometry; mapped back, checked
// forward-backward and against the verified model.
void DescriptorLinker::GuidedKlt(const DescribedFrame& key, const DescribedFrame& current,
                                 LinkResult* result) const {
  std::unordered_set<long> carried(result->ids.begin(), result->ids.end());
  std::vector<cv::Point2f> from;
  std::vector<long> from_ids;
  for (size_t i = 0; i < key.points.size(); ++i)
    if (!carried.count(key.ids[i])) {
      from.push_back(key.points[i]);
      from_ids.push_back(key.ids[i]);
    }
  if (from.empty()) return;
  const cv::Matx33d h(result->current_from_key);
  cv::Mat warped;  // warped(x) = current(h x)
  cv::warpPerspective(current.gray, warped, h, key.gray.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                      cv::BORDER_REPLICATE);
  // After the warp only the residual (parallax, the warp's error) is left:
  // two levels reach ~2 windows. The coarse levels of a zoom-in's warp
  // would see mostly the border outside the current view and wander off.
  std::vector<cv::Mat> key_pyramid, warped_pyramid;
  PyramidLkOptions lk = options_.lk;
  lk.max_level = std::min(lk.max_level, 1);
  cv::buildOpticalFlowPyramid(key.gray, key_pyramid, lk.window, lk.max_level, true);
  cv::buildOpticalFlowPyramid(warped, warped_pyramid, lk.window, lk.max_level, true);
  std::vector<cv::Point2f> forward = from, backward;
  std::vector<unsigned char> ok_f, ok_b;
  PyramidLk(key_pyramid, warped_pyramid, from, &forward, &ok_f, lk, true);
  backward = from;
  PyramidLk(warped_pyramid, key_pyramid, forward, &backward, &ok_b, lk, true);
  const double fb2 = options_.fb_threshold_px * options_.fb_threshold_px;
  const float max_x = static_cast<float>(current.gray.cols - 1), max_y = static_cast<float>(current.gray.rows - 1);
  for (size_t i = 0; i < from.size(); ++i) {
    const cv::Point2f e = backward[i] - from[i];
    if (!ok_f[i] || !ok_b[i] || !(e.dot(e) <= fb2)) continue;
    const cv::Point2f p = Apply(h, forward[i]);
    if (!(p.x >= 0 && p.y >= 0 && p.x <= max_x && p.y <= max_y)) continue;
    if (!Agrees(*result, from[i], p)) continue;
    result->points.push_back(p);
    result->ids.push_back(from_ids[i]);
    result->key_points.push_back(from[i]);
  }
}

bool DescriptorLinker::Agrees(const LinkResult& link, const cv::Point2f& key_point,
                              const cv::Point2f& point) const {
  if (link.model == LinkModel::kFundamental)
    return EpipolarDistance(cv::Matx33d(link.fundamental), key_point, point) <= options_.fundamental_px;
  if (link.model == LinkModel::kHomography)
    return cv::norm(Apply(cv::Matx33d(link.current_from_key), key_point) - point) <= options_.homography_px;
  return false;
}

}  // namespace hapcine
