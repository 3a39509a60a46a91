#include "extract/shot_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "core/statistics.h"

namespace hapcine {
namespace {

constexpr size_t kWindow = 30;
constexpr int kMinCalmBeforeCandidate = 3;
constexpr int kMaxCandidateLen = 90;
// Spikes: d >= kSpikeRatio x median of the last kLocalWindow distances (at
// least kMinLocal of them) and d >= kSpikeFloor. Measured on the 17 synth
// clips (docs/extract.md): a cut after a pan is 2.95x the median of the
// pan before it; inside a whip pan's tracking collapse the ratio is
// 0.75-0.92. The floor keeps compression flicker on a still picture (median
// ~0) from counting.
constexpr size_t kLocalWindow = 5;
constexpr size_t kMinLocal = 3;
constexpr double kSpikeRatio = 2.0;
constexpr double kSpikeFloor = 0.02;

// Statistics only (histogram, mean, std-dev), so point sampling is enough:
// nearest-neighbour decimation costs ~50 us where area averaging of a
// 960-px BGR frame costs over a millisecond.
cv::Mat Thumb(const cv::Mat& image) {
  if (image.cols <= kShotThumbWidth) return image;
  const int h =
      std::max(1, static_cast<int>(std::lround(image.rows * double(kShotThumbWidth) / image.cols)));
  cv::Mat small;
  cv::resize(image, small, cv::Size(kShotThumbWidth, h), 0, 0, cv::INTER_NEAREST);
  return small;
}

cv::Mat Histogram(const Frame& frame, const cv::Mat& gray_thumb) {
  cv::Mat hist;
  if (!frame.bgr.empty()) {
    cv::Mat hsv;
    cv::cvtColor(Thumb(frame.bgr), hsv, cv::COLOR_BGR2HSV);
    const int channels[] = {0, 1, 2};
    const int sizes[] = {16, 4, 8};
    const float h_range[] = {0, 180}, s_range[] = {0, 256}, v_range[] = {0, 256};
    const float* ranges[] = {h_range, s_range, v_range};
    cv::calcHist(&hsv, 1, channels, cv::Mat(), hist, 3, sizes, ranges);
  } else {
    const int channels[] = {0};
    const int sizes[] = {64};
    const float range[] = {0, 256};
    const float* ranges[] = {range};
    cv::calcHist(&gray_thumb, 1, channels, cv::Mat(), hist, 1, sizes, ranges);
  }
  const double total = cv::sum(hist)[0];
  if (total > 0) hist /= total;
  return hist;
}

// The picture's layout for the continuity test: a 64-px-wide gray
// thumbnail, blurred (sigma 1.5 px, ~2 % of the width) so that motion blur
// and compression make little difference, as float for matchTemplate.
cv::Mat Layout(const cv::Mat& gray_thumb) {
  const int h = std::max(
      8, static_cast<int>(std::lround(gray_thumb.rows * double(kLayoutWidth) / gray_thumb.cols)));
  cv::Mat small, f;
  cv::resize(gray_thumb, small, cv::Size(kLayoutWidth, h), 0, 0, cv::INTER_AREA);
  small.convertTo(f, CV_32F);
  cv::GaussianBlur(f, f, cv::Size(0, 0), 1.5);
  return f;
}

// Best normalised cross-correlation of the middle of `before` (3/5 of each
// side) anywhere in `now`: shifts up to a fifth of each side, the motion
// of a fast handheld move or a pan between two frames. 1 for a flat
// template (nothing to compare: no evidence of a cut).
double Continuity(const cv::Mat& before, const cv::Mat& now) {
  if (before.empty() || now.empty() || before.size() != now.size()) return 0;
  const cv::Rect middle(before.cols / 5, before.rows / 5, before.cols - 2 * (before.cols / 5),
                        before.rows - 2 * (before.rows / 5));
  const cv::Mat templ = before(middle);
  cv::Scalar mean, stddev;
  cv::meanStdDev(templ, mean, stddev);
  if (stddev[0] < 1.0) return 1;
  cv::Mat score;
  cv::matchTemplate(now, templ, score, cv::TM_CCOEFF_NORMED);
  double best = 0;
  cv::minMaxLoc(score, nullptr, &best);
  return std::isfinite(best) ? best : 0;
}

double Distance(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty() || a.total() != b.total()) return 1.0;
  const double d = cv::compareHist(a, b, cv::HISTCMP_BHATTACHARYYA);
  return std::isfinite(d) ? std::clamp(d, 0.0, 1.0) : 1.0;
}

}  // namespace

namespace {

// NCC of a and b over mask; NaN when either is flat there.
double MaskedNcc(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  cv::Scalar mean_a, std_a, mean_b, std_b;
  cv::meanStdDev(a, mean_a, std_a, mask);
  cv::meanStdDev(b, mean_b, std_b, mask);
  if (std_a[0] < 1.0 || std_b[0] < 1.0) return std::numeric_limits<double>::quiet_NaN();
  cv::Mat ab;
  cv::multiply(a - mean_a[0], b - mean_b[0], ab);
  return cv::mean(ab, mask)[0] / (std_a[0] * std_b[0]);
}

}  // namespace

double MovedPictureChange(const cv::Mat& before, const cv::Mat& now,
                          const cv::Matx33d& now_from_before, cv::Size working) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (before.empty() || now.empty() || before.size() != now.size() || working.width <= 0 ||
      working.height <= 0)
    return nan;
  // Working pixels -> layout pixels (pixel edges scale).
  const double sx = double(now.cols) / working.width, sy = double(now.rows) / working.height;
  const cv::Matx33d to_layout(sx, 0, 0.5 * sx - 0.5, 0, sy, 0.5 * sy - 0.5, 0, 0, 1);
  const cv::Matx33d moved = to_layout * now_from_before * to_layout.inv();
  cv::Mat warped, covered;
  cv::warpPerspective(before, warped, moved, now.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::warpPerspective(cv::Mat(before.size(), CV_8UC1, cv::Scalar(255)), covered, moved, now.size(),
                      cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  // Away from the covered part's edge, where the warp mixes in the border.
  cv::erode(covered, covered, cv::Mat(), cv::Point(-1, -1), 2);
  int cells = 0, changed = 0;
  for (int gy = 0; gy < kChangeGridRows; ++gy) {
    for (int gx = 0; gx < kChangeGridCols; ++gx) {
      const cv::Rect cell(gx * now.cols / kChangeGridCols, gy * now.rows / kChangeGridRows,
                          now.cols / kChangeGridCols, now.rows / kChangeGridRows);
      const cv::Mat mask = covered(cell);
      if (cv::countNonZero(mask) < 0.5 * cell.area()) continue;
      const double c = MaskedNcc(warped(cell), now(cell), mask);
      if (std::isnan(c)) continue;
      ++cells;
      changed += c < kContinuousPicture;
    }
  }
  if (cells < kChangeGridCols * kChangeGridRows / 3) return nan;
  return static_cast<double>(changed) / cells;
}

bool ShotDetector::IsSpike(double d, double calm_limit) const {
  if (local_.size() < kMinLocal || d < kSpikeFloor || d < calm_limit) return false;
  return d >= kSpikeRatio * Median(std::vector<double>(local_.begin(), local_.end()));
}

double ShotDetector::UpdateLayout(const cv::Mat& gray_thumb) {
  const cv::Mat layout = Layout(gray_thumb);
  const double continuity =
      !in_blank_run_ && !prev_layout_.empty() ? Continuity(prev_layout_, layout) : 1.0;
  prev_layout_ = layout;
  layout_ = layout;
  return continuity;
}

void ShotDetector::RecentStatistics(double* mean, double* stddev) const {
  *mean = *stddev = 0;
  if (recent_.empty()) return;
  for (double x : recent_) *mean += x;
  *mean /= recent_.size();
  for (double x : recent_) *stddev += (x - *mean) * (x - *mean);
  *stddev = std::sqrt(*stddev / recent_.size());
}

void ShotDetector::StartShot() {
  recent_.clear();
  local_.clear();
  calm_frames_ = 0;
  candidate_ = false;
  candidate_len_ = 0;
  candidate_start_hist_.release();
}

ShotDecision ShotDetector::Update(const Frame& frame) {
  ShotDecision out;
  const cv::Mat gray_thumb = Thumb(frame.gray);
  cv::Scalar mean, stddev;
  cv::meanStdDev(gray_thumb, mean, stddev);
  out.mean_luma = mean[0];
  out.luma_stddev = stddev[0];
  out.blank = mean[0] < options_.blank_luma || stddev[0] < options_.blank_stddev;
  if (out.blank) {
    layout_.release();
    in_blank_run_ = true;
    candidate_ = false;
    candidate_len_ = 0;
    return out;
  }
  const cv::Mat hist = Histogram(frame, gray_thumb);
  out.continuity = UpdateLayout(gray_thumb);
  if (in_blank_run_ || prev_hist_.empty()) {
    // First content after black (or the very first frame).
    if (in_blank_run_ && shot_has_content_) out.boundary = ShotBoundary::kFade;
    // Right after black is where a fade-in starts: flag it like a transition.
    out.transition = in_blank_run_;
    in_blank_run_ = false;
    shot_has_content_ = true;
    StartShot();
    prev_hist_ = hist;
    return out;
  }

  const cv::Mat before = prev_hist_;
  const double d = Distance(before, hist);
  out.distance = d;
  prev_hist_ = hist;
  double mean_d = 0, std_d = 0;
  RecentStatistics(&mean_d, &std_d);
  const bool stats_ok = recent_.size() >= 5;
  const double t_cut =
      stats_ok ? std::max(options_.cut_threshold, mean_d + 6 * std_d) : options_.cut_threshold;
  const double t_low = stats_ok ? std::max(0.1 * options_.cut_threshold, mean_d + 3 * std_d)
                                : 0.1 * options_.cut_threshold;
  out.spike = IsSpike(d, stats_ok ? mean_d + 6 * std_d : 0.0);
  local_.push_back(d);
  if (local_.size() > kLocalWindow) local_.pop_front();

  if (d > t_cut) {
    out.boundary = ShotBoundary::kCut;
    StartShot();
    return out;
  }
  if (d > t_low) {
    if (!candidate_) {
      candidate_ = true;
      candidate_len_ = 0;
      candidate_allowed_boundary_ = calm_frames_ >= kMinCalmBeforeCandidate;
      candidate_start_hist_ = before;  // the last frame before the run
    }
    ++candidate_len_;
    out.transition = true;
    if (candidate_len_ > kMaxCandidateLen) {  // slow drift, not a transition
      candidate_ = false;
      calm_frames_ = 0;
    }
    return out;
  }
  if (candidate_) {
    candidate_ = false;
    const double total = Distance(candidate_start_hist_, hist);
    if (candidate_allowed_boundary_ && candidate_len_ >= 2 && total > options_.cut_threshold) {
      out.boundary = ShotBoundary::kFade;
      StartShot();
      return out;
    }
    out.look_alike_run_ended = candidate_allowed_boundary_ && candidate_len_ >= 2;
  }
  recent_.push_back(d);
  if (recent_.size() > kWindow) recent_.pop_front();
  ++calm_frames_;
  return out;
}

}  // namespace hapcine
