// See appearance_check.h.
#include "extract/appearance_check.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_set>

namespace hapcine {

namespace {
// Below this standard deviation (grey levels) a patch is flat: sensor noise
// and compression dominate its NCC.
constexpr double kFlatStddev = 2.0;
}  // namespace

bool NormalizedPatch(const cv::Mat& gray, cv::Point2f at, int side, cv::Mat* patch) {
  patch->release();
  cv::Mat raw;
  // getRectSubPix replicates the border for a window reaching outside.
  cv::getRectSubPix(gray, cv::Size(side, side), at, raw, CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(raw, mean, stddev);
  if (!(stddev[0] >= kFlatStddev)) return false;
  raw -= mean[0];
  raw /= stddev[0] * std::sqrt(static_cast<double>(side * side));
  *patch = raw;
  return true;
}

double PatchNcc(const cv::Mat& a, const cv::Mat& b) { return a.dot(b); }

void AppearanceCheck::Born(const cv::Mat& gray, cv::Point2f at, long id) {
  std::deque<cv::Mat>& h = history_[id];
  h.clear();
  h.emplace_back();
  NormalizedPatch(gray, at, side_, &h.back());
}

void AppearanceCheck::Score(const cv::Mat& gray, const std::vector<cv::Point2f>& points,
                            const std::vector<long>& ids, std::vector<float>* ncc) {
  ncc->assign(points.size(), 1.0f);
  std::unordered_set<long> live(ids.begin(), ids.end());
  for (auto it = history_.begin(); it != history_.end();)
    it = live.count(it->first) ? std::next(it) : history_.erase(it);
  for (size_t i = 0; i < points.size(); ++i) {
    auto found = history_.find(ids[i]);
    if (found == history_.end()) {
      Born(gray, points[i], ids[i]);
      continue;
    }
    std::deque<cv::Mat>& h = found->second;
    cv::Mat now;
    const bool textured = NormalizedPatch(gray, points[i], side_, &now);
    if (textured && !h.front().empty()) (*ncc)[i] = static_cast<float>(PatchNcc(h.front(), now));
    if (lag_ > 0) {
      h.push_back(std::move(now));
      if (static_cast<int>(h.size()) > lag_) h.pop_front();
    }
  }
}

}  // namespace hapcine
