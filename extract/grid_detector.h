#pragma once
// Corner detections spread over a grid: Shi-Tomasi minimum-eigenvalue
// response (the goodFeaturesToTrack measure), 3x3 non-maximum suppression,
// strongest first, at most `per_cell` per grid cell, never closer than
// min_distance_px to each other or to an existing (live) point.

#include <opencv2/core.hpp>
#include <vector>

namespace hapcine {

struct GridDetectorOptions {
  int grid_cols = 8, grid_rows = 6;
  int per_cell = 13;            // detections (incl. existing points) per cell
  double min_distance_px = 8;   // working pixels
  double quality_level = 0.01;  // response relative to the image's strongest
  int border_px = 8;            // no detections this close to the edge
};

// Appends new corners to *out; `existing` are live points (masked out and
// counted against their cell's quota). Returns how many were added.
int DetectGridCorners(const cv::Mat& gray, const std::vector<cv::Point2f>& existing, int max_new,
                      const GridDetectorOptions& options, std::vector<cv::Point2f>* out);

}  // namespace hapcine
