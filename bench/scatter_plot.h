#pragma once
// A small x-y chart for the benchmark report, drawn with OpenCV and written
// as PNG: series of points with markers, optionally joined by a line, on
// linear or log10 axes. (datasets/plot_figure.h draws time series that share
// an x axis; the benchmark needs scatter points and log axes, hence this.)

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace hapcine::bench {

struct ScatterSeries {
  std::string name;                 // legend entry
  std::vector<double> x, y;         // same length; non-finite or (log axis) <= 0 points are skipped
  std::vector<std::string> labels;  // optional, one per point, drawn beside it
  bool line = false;                // join the points in the given order
  int color_index = 0;              // palette index
  int marker = 0;                   // 0 circle, 1 square, 2 triangle, 3 diamond
};

struct ScatterChart {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  bool y_from_zero = false;  // linear y axis starting at 0
  // Category axis: when set, x ticks sit at 1..N with these labels.
  std::vector<std::string> x_categories;
  int width_px = 900, height_px = 560;
  std::vector<ScatterSeries> series;
};

// Throws hapcine::Error when there is nothing to draw.
cv::Mat RenderScatter(const ScatterChart& chart);  // CV_8UC3
// Atomic PNG write (temporary name, then rename); throws hapcine::Error.
void WriteScatterPng(const ScatterChart& chart, const std::string& file);

// Where each point's label goes: the box (text of `sizes[i]`) to the upper
// right of `anchors[i]`, else the first of lower right, upper left, lower
// left, then the same one to three lines further out, that overlaps no box
// placed before it nor a point and stays inside `bounds`; when none does,
// the upper right. Points close together (two settings with the same error)
// would otherwise print over each other.
std::vector<cv::Rect> PlaceLabels(const std::vector<cv::Point>& anchors, const std::vector<cv::Size>& sizes,
                                  const cv::Rect& bounds);

// Tick positions for [lo, hi]: 1-2-5 steps on a linear axis, 1-2-5 per
// decade on a log axis (values, not logs).
std::vector<double> AxisTicks(double lo, double hi, bool log);

}  // namespace hapcine::bench
