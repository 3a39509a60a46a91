#include "extract/pyramid_lk.h"

#include <algorithm>
#include <opencv2/video/tracking.hpp>

#include "core/error.h"

namespace hapcine {

void PyramidLk(const std::vector<cv::Mat>& from_pyramid, const std::vector<cv::Mat>& to_pyramid,
               const std::vector<cv::Point2f>& from, std::vector<cv::Point2f>* to,
               std::vector<unsigned char>* status, const PyramidLkOptions& options,
               bool use_initial_flow) {
  // Pyramids with derivatives hold two Mats a level.
  const int levels = static_cast<int>(std::min(from_pyramid.size(), to_pyramid.size()) / 2);
  if (levels < 1) throw Error("PyramidLk", "pyramids must be built with derivatives");
  const int max_level = std::min(options.max_level, levels - 1);
  if (from.empty()) {
    to->clear();
    status->clear();
    return;
  }
  if (use_initial_flow && to->size() != from.size())
    throw Error("PyramidLk", "initial flow must have one point per input point");
  if (!use_initial_flow) *to = from;
  if (max_level > 0) {
    // Levels 1..max_level: the pyramids from level 1, points halved (exact
    // in float, as OpenCV's own per-level scaling by powers of two is).
    const std::vector<cv::Mat> from_coarse(from_pyramid.begin() + 2, from_pyramid.end());
    const std::vector<cv::Mat> to_coarse(to_pyramid.begin() + 2, to_pyramid.end());
    std::vector<cv::Point2f> from_half(from.size()), to_half(from.size());
    for (size_t i = 0; i < from.size(); ++i) {
      from_half[i] = from[i] * 0.5f;
      to_half[i] = (*to)[i] * 0.5f;
    }
    // OpenCV marks failures at level 0 only; the coarse call's statuses
    // (its level 0 is our level 1) are ignored, and its point carried down
    // as OpenCV carries it.
    std::vector<unsigned char> coarse_status;
    cv::calcOpticalFlowPyrLK(from_coarse, to_coarse, from_half, to_half, coarse_status,
                             cv::noArray(), options.window, max_level - 1, options.coarse,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    for (size_t i = 0; i < from.size(); ++i) (*to)[i] = to_half[i] * 2.f;
  }
  cv::calcOpticalFlowPyrLK(from_pyramid, to_pyramid, from, *to, *status, cv::noArray(),
                           options.window, 0, options.fine,
                           max_level > 0 || use_initial_flow ? cv::OPTFLOW_USE_INITIAL_FLOW : 0);
}

}  // namespace hapcine
