#pragma once
// Pyramidal Lucas-Kanade (cv::calcOpticalFlowPyrLK) in two calls: the coarse
// levels, whose answer only seeds the next finer level, with a looser stop
// criterion, then the finest level with the full one.
//
// OpenCV applies one criterion (30 iterations or a step below 0.01 px) at
// every level, so the coarse levels, each as costly per iteration as the
// finest, iterate to a precision that the next level discards. The split is
// exact when both criteria are the same (same float operations, same
// answer; pyramid_lk_test.cc), and status is only decided at level 0, as in
// OpenCV. The error output is never computed (one window pass per point
// that the tracker did not use).

#include <opencv2/core.hpp>
#include <vector>

namespace hapcine {

struct PyramidLkOptions {
  cv::Size window{21, 21};
  int max_level = 3;  // pyramid levels - 1
  cv::TermCriteria fine{cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01};
  cv::TermCriteria coarse{cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01};
};

// `from_pyramid` / `to_pyramid`: cv::buildOpticalFlowPyramid output with
// derivatives ({image0, derivatives0, image1, ...}). `to` is read as the
// initial guess when use_initial_flow, and receives the tracked positions.
void PyramidLk(const std::vector<cv::Mat>& from_pyramid, const std::vector<cv::Mat>& to_pyramid,
               const std::vector<cv::Point2f>& from, std::vector<cv::Point2f>* to,
               std::vector<unsigned char>* status, const PyramidLkOptions& options,
               bool use_initial_flow = false);

}  // namespace hapcine
