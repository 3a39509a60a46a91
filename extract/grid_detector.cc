#include "extract/grid_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace hapcine {
namespace {

// Buckets of side min_distance: a point only needs checking against the
// 3x3 buckets around it.
class Occupancy {
 public:
  Occupancy(cv::Size size, double min_distance)
      : cell_(std::max(1.0, min_distance)),
        min_d2_(min_distance * min_distance),
        cols_(static_cast<int>(std::ceil(size.width / cell_)) + 1),
        rows_(static_cast<int>(std::ceil(size.height / cell_)) + 1),
        buckets_(static_cast<size_t>(cols_) * rows_) {}

  bool Free(const cv::Point2f& p) const {
    const int cx = Col(p.x), cy = Row(p.y);
    for (int y = std::max(0, cy - 1); y <= std::min(rows_ - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(cols_ - 1, cx + 1); ++x)
        for (const cv::Point2f& q : buckets_[y * cols_ + x]) {
          const float dx = p.x - q.x, dy = p.y - q.y;
          if (dx * dx + dy * dy < min_d2_) return false;
        }
    return true;
  }
  void Add(const cv::Point2f& p) { buckets_[Row(p.y) * cols_ + Col(p.x)].push_back(p); }

 private:
  int Col(float x) const { return std::clamp(static_cast<int>(x / cell_), 0, cols_ - 1); }
  int Row(float y) const { return std::clamp(static_cast<int>(y / cell_), 0, rows_ - 1); }
  double cell_, min_d2_;
  int cols_, rows_;
  std::vector<std::vector<cv::Point2f>> buckets_;
};

}  // namespace

int DetectGridCorners(const cv::Mat& gray, const std::vector<cv::Point2f>& existing, int max_new,
                      const GridDetectorOptions& options, std::vector<cv::Point2f>* out) {
  if (max_new <= 0 || gray.empty()) return 0;
  const int w = gray.cols, h = gray.rows;
  const int gc = std::max(1, options.grid_cols), gr = std::max(1, options.grid_rows);
  auto cell_of = [&](const cv::Point2f& p) {
    const int cx = std::clamp(static_cast<int>(p.x * gc / w), 0, gc - 1);
    const int cy = std::clamp(static_cast<int>(p.y * gr / h), 0, gr - 1);
    return cy * gc + cx;
  };
  std::vector<int> count(static_cast<size_t>(gc) * gr, 0);
  Occupancy occupancy(gray.size(), options.min_distance_px);
  for (const cv::Point2f& p : existing) {
    ++count[cell_of(p)];
    occupancy.Add(p);
  }
  bool any_room = false;
  for (int c : count) any_room |= c < options.per_cell;
  if (!any_room) return 0;

  // Reused between calls: two float images per frame would otherwise be
  // fresh mmap'ed pages (page faults) every time.
  thread_local cv::Mat response, dilated;
  cv::cornerMinEigenVal(gray, response, 3, 3);
  double max_response = 0;
  cv::minMaxLoc(response, nullptr, &max_response);
  if (!(max_response > 0)) return 0;
  const float threshold = static_cast<float>(max_response * options.quality_level);
  cv::dilate(response, dilated, cv::Mat());

  // Candidates per cell; each cell keeps only its strongest few (a cell
  // can take at most per_cell points, some rejected by spacing), so no big
  // global sort: textured or noisy frames have 10^5 local maxima.
  struct Candidate {
    float response;
    cv::Point2f p;
  };
  auto stronger = [](const Candidate& a, const Candidate& c) { return a.response > c.response; };
  std::vector<std::vector<Candidate>> cells(count.size());
  const size_t keep = static_cast<size_t>(std::max(1, options.per_cell)) * 4;
  const int b = std::max(1, options.border_px);
  for (int y = b; y < h - b; ++y) {
    const float* r = response.ptr<float>(y);
    const float* d = dilated.ptr<float>(y);
    const int cy = std::min(gr - 1, y * gr / h);
    for (int x = b; x < w - b; ++x) {
      if (!(r[x] > threshold) || r[x] != d[x]) continue;
      const int cell = cy * gc + std::min(gc - 1, x * gc / w);
      if (count[cell] >= options.per_cell) continue;
      std::vector<Candidate>& list = cells[cell];
      list.push_back({r[x], cv::Point2f(static_cast<float>(x), static_cast<float>(y))});
      if (list.size() >= 8 * keep) {  // bound memory and sort work
        std::nth_element(list.begin(), list.begin() + keep, list.end(), stronger);
        list.resize(keep);
      }
    }
  }
  std::vector<Candidate> candidates;
  for (auto& list : cells) {
    if (list.size() > keep) {
      std::nth_element(list.begin(), list.begin() + keep, list.end(), stronger);
      list.resize(keep);
    }
    candidates.insert(candidates.end(), list.begin(), list.end());
  }
  std::sort(candidates.begin(), candidates.end(), stronger);
  int added = 0;
  for (const Candidate& c : candidates) {
    if (added >= max_new) break;
    const int cell = cell_of(c.p);
    if (count[cell] >= options.per_cell || !occupancy.Free(c.p)) continue;
    ++count[cell];
    occupancy.Add(c.p);
    out->push_back(c.p);
    ++added;
  }
  return added;
}

}  // namespace hapcine
