#include "bench/scatter_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine::bench {
namespace {

// Tableau 10, BGR.
cv::Scalar Palette(int i) {
  static const int rgb[10][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},
                                 {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127},
                                 {188, 189, 34},  {23, 190, 207}};
  const int* c = rgb[((i % 10) + 10) % 10];
  return cv::Scalar(c[2], c[1], c[0]);
}

bool Usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

std::string TickText(double v) {
  char buf[32];
  if (v != 0 && (std::fabs(v) >= 1e4 || std::fabs(v) < 1e-3))
    std::snprintf(buf, sizeof(buf), "%.0e", v);
  else
    std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

void DrawMarker(cv::Mat& img, cv::Point p, int marker, const cv::Scalar& color) {
  const int r = 6;
  switch (marker % 4) {
    case 0: cv::circle(img, p, r, color, cv::FILLED, cv::LINE_AA); break;
    case 1: cv::rectangle(img, p - cv::Point(r - 1, r - 1), p + cv::Point(r - 1, r - 1), color, cv::FILLED); break;
    case 2: {
      std::vector<cv::Point> tri{p + cv::Point(0, -r - 1), p + cv::Point(r, r - 1), p + cv::Point(-r, r - 1)};
      cv::fillConvexPoly(img, tri, color, cv::LINE_AA);
      break;
    }
    default: {
      std::vector<cv::Point> dia{p + cv::Point(0, -r - 1), p + cv::Point(r + 1, 0), p + cv::Point(0, r + 1),
                                 p + cv::Point(-r - 1, 0)};
      cv::fillConvexPoly(img, dia, color, cv::LINE_AA);
    }
  }
}

}  // namespace

std::vector<double> AxisTicks(double lo, double hi, bool log) {
  std::vector<double> ticks;
  if (!(hi > lo)) return {lo};
  if (log) {
    const int d0 = static_cast<int>(std::floor(std::log10(lo))), d1 = static_cast<int>(std::ceil(std::log10(hi)));
    // Fewer labels over many decades: only the powers of ten.
    const bool sparse = d1 - d0 > 3;
    for (int d = d0; d <= d1; ++d)
      for (double m : {1.0, 2.0, 5.0}) {
        if (sparse && m != 1.0) continue;
        const double v = m * std::pow(10.0, d);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
      }
    return ticks;
  }
  const double raw = (hi - lo) / 6;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) { step = m * mag; break; }
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    ticks.push_back(std::fabs(v) < step * 1e-9 ? 0 : v);
  return ticks;
}

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225);

// Pad a range (a factor on log axes) so markers are not on the frame.
void PadRange(double& lo, double& hi, bool log) {
  if (log) {
    if (hi / lo < 10) { const double m = std::sqrt(10 / (hi / lo)); lo /= m; hi *= m; }
    lo /= 1.3;
    hi *= 1.3;
  } else {
    double span = hi - lo;
    if (span <= 0) span = std::max(1.0, std::fabs(hi));
    lo -= 0.08 * span;
    hi += 0.08 * span;
  }
}

// The plotted ranges and where they go in the image.
struct PlotFrame {
  double x_lo, x_hi, y_lo, y_hi;
  bool log_x, log_y;
  cv::Rect area;  // the axes' box, pixels

  static double Fraction(double v, double lo, double hi, bool log) {
    return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
  }
  cv::Point ToPx(double x, double y) const {
    return cv::Point(static_cast<int>(std::lround(area.x + area.width * Fraction(x, x_lo, x_hi, log_x))),
                     static_cast<int>(std::lround(area.y + area.height * (1 - Fraction(y, y_lo, y_hi, log_y)))));
  }
};

// The usable points' ranges, padded; throws when there is no point.
PlotFrame DataRanges(const ScatterChart& chart) {
  PlotFrame f;
  f.log_x = chart.log_x;
  f.log_y = chart.log_y;
  f.x_lo = f.y_lo = std::numeric_limits<double>::infinity();
  f.x_hi = f.y_hi = -f.x_lo;
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size()) throw Error(chart.title, "series '" + s.name + "' has x/y of different lengths");
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!Usable(s.x[i], chart.log_x) || !Usable(s.y[i], chart.log_y)) continue;
      f.x_lo = std::min(f.x_lo, s.x[i]);
      f.x_hi = std::max(f.x_hi, s.x[i]);
      f.y_lo = std::min(f.y_lo, s.y[i]);
      f.y_hi = std::max(f.y_hi, s.y[i]);
    }
  }
  if (!std::isfinite(f.x_lo) || !std::isfinite(f.y_lo)) throw Error(chart.title, "no point to plot");
  PadRange(f.x_lo, f.x_hi, chart.log_x);
  const bool from_zero = chart.y_from_zero && !chart.log_y && f.y_lo >= 0;
  if (from_zero) f.y_lo = 0;
  PadRange(f.y_lo, f.y_hi, chart.log_y);
  if (from_zero) f.y_lo = 0;  // padding only above
  return f;
}

constexpr int kLeft = 80, kTop = 64;

// The axes' box: the legend column on the right is as wide as the longest
// name; two rows of category labels need more room below.
cv::Rect PlotArea(const ScatterChart& chart) {
  int legend_w = 0;
  for (const auto& s : chart.series)
    legend_w = std::max(legend_w, cv::getTextSize(s.name, kFont, 0.45, 1, nullptr).width);
  const int right = legend_w + 60, bottom = chart.x_categories.empty() ? 60 : 76;
  const cv::Rect area(kLeft, kTop, chart.width_px - kLeft - right, chart.height_px - kTop - bottom);
  if (area.width < 50 || area.height < 50) throw Error(chart.title, "chart too small");
  return area;
}

void DrawXAxis(cv::Mat& img, const ScatterChart& chart, const PlotFrame& f) {
  const cv::Rect& area = f.area;
  if (chart.x_categories.empty()) {
    for (double t : AxisTicks(f.x_lo, f.x_hi, chart.log_x)) {
      const int px = f.ToPx(t, f.y_lo).x;
      cv::line(img, {px, area.y}, {px, area.y + area.height}, kGrid, 1);
      const std::string s = TickText(t);
      cv::putText(img, s, {px - 4 * static_cast<int>(s.size()), area.y + area.height + 20}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
    }
    return;
  }
  // Labels on two alternating rows so neighbours do not overlap.
  for (size_t k = 0; k < chart.x_categories.size(); ++k) {
    const double t = k + 1.0;
    if (t < f.x_lo || t > f.x_hi) continue;
    const int px = f.ToPx(t, f.y_lo).x;
    cv::line(img, {px, area.y}, {px, area.y + area.height}, kGrid, 1);
    const std::string& s = chart.x_categories[k];
    const int w = cv::getTextSize(s, kFont, 0.38, 1, nullptr).width;
    cv::putText(img, s, {px - w / 2, area.y + area.height + 18 + 16 * static_cast<int>(k % 2)}, kFont, 0.38, kBlack, 1,
                cv::LINE_AA);
  }
}

// The y grid and ticks, the box, the title and the axis labels.
void DrawYAxisAndTitles(cv::Mat& img, const ScatterChart& chart, const PlotFrame& f) {
  const cv::Rect& area = f.area;
  for (double t : AxisTicks(f.y_lo, f.y_hi, chart.log_y)) {
    const int py = f.ToPx(f.x_lo, t).y;
    cv::line(img, {area.x, py}, {area.x + area.width, py}, kGrid, 1);
    const std::string s = TickText(t);
    cv::putText(img, s, {area.x - 10 - 9 * static_cast<int>(s.size()), py + 5}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }
  cv::rectangle(img, area, kBlack, 1);
  cv::putText(img, chart.title, {kLeft, 26}, kFont, 0.65, kBlack, 1, cv::LINE_AA);
  cv::putText(img, chart.x_label, {area.x + area.width / 2 - 4 * static_cast<int>(chart.x_label.size()),
                                   chart.height_px - 18}, kFont, 0.5, kBlack, 1, cv::LINE_AA);
  cv::putText(img, chart.y_label, {8, kTop - 10}, kFont, 0.5, kBlack, 1, cv::LINE_AA);
}

// Every series' points in pixels; then their labels, placed all at once so
// that they avoid each other across series.
std::vector<std::vector<cv::Point>> DrawPointLabels(cv::Mat& img, const ScatterChart& chart, const PlotFrame& f) {
  std::vector<std::vector<cv::Point>> points(chart.series.size());
  std::vector<cv::Point> label_anchor;
  std::vector<cv::Size> label_size;
  std::vector<std::pair<size_t, size_t>> label_of;  // (series, point index in the series)
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const ScatterSeries& s = chart.series[k];
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!Usable(s.x[i], chart.log_x) || !Usable(s.y[i], chart.log_y)) continue;
      points[k].push_back(f.ToPx(s.x[i], s.y[i]));
      if (i < s.labels.size() && !s.labels[i].empty()) {
        label_anchor.push_back(points[k].back());
        label_size.push_back(cv::getTextSize(s.labels[i], kFont, 0.38, 1, nullptr));
        label_of.push_back({k, i});
      }
    }
  }
  const std::vector<cv::Rect> boxes =
      PlaceLabels(label_anchor, label_size, cv::Rect(0, 0, f.area.x + f.area.width + 10, chart.height_px));
  for (size_t j = 0; j < boxes.size(); ++j) {
    const ScatterSeries& s = chart.series[label_of[j].first];
    cv::putText(img, s.labels[label_of[j].second], {boxes[j].x, boxes[j].y + boxes[j].height}, kFont, 0.38,
                Palette(s.color_index), 1, cv::LINE_AA);
  }
  return points;
}

// Each series' line and markers, and its legend entry (none for a series
// with nothing drawn).
void DrawSeriesAndLegend(cv::Mat& img, const ScatterChart& chart, const cv::Rect& area,
                         const std::vector<std::vector<cv::Point>>& points) {
  int legend_y = kTop + 10;
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const ScatterSeries& s = chart.series[k];
    const cv::Scalar color = Palette(s.color_index);
    const std::vector<cv::Point>& pts = points[k];
    if (s.line && pts.size() > 1) cv::polylines(img, pts, false, color, 2, cv::LINE_AA);
    for (const auto& p : pts) DrawMarker(img, p, s.marker, color);
    if (!s.name.empty() && !pts.empty()) {
      const cv::Point lp(area.x + area.width + 20, legend_y);
      if (s.line) cv::line(img, lp + cv::Point(-8, 0), lp + cv::Point(8, 0), color, 2, cv::LINE_AA);
      DrawMarker(img, lp, s.marker, color);
      cv::putText(img, s.name, lp + cv::Point(16, 5), kFont, 0.45, kBlack, 1, cv::LINE_AA);
      legend_y += 24;
    }
  }
}

}  // namespace

cv::Mat RenderScatter(const ScatterChart& chart) {
  PlotFrame frame = DataRanges(chart);
  cv::Mat img(chart.height_px, chart.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  frame.area = PlotArea(chart);
  DrawXAxis(img, chart, frame);
  DrawYAxisAndTitles(img, chart, frame);
  const std::vector<std::vector<cv::Point>> points = DrawPointLabels(img, chart, frame);
  DrawSeriesAndLegend(img, chart, frame.area, points);
  return img;
}

std::vector<cv::Rect> PlaceLabels(const std::vector<cv::Point>& anchors, const std::vector<cv::Size>& sizes,
                                  const cv::Rect& bounds) {
  std::vector<cv::Rect> placed;
  auto free_at = [&](const cv::Rect& r) {
    if ((r & bounds) != r) return false;
    for (const cv::Rect& q : placed)
      if ((r & q).area() > 0) return false;
    for (const cv::Point& p : anchors)  // the markers (radius ~5 px)
      if ((r & cv::Rect(p.x - 5, p.y - 5, 11, 11)).area() > 0) return false;
    return true;
  };
  for (size_t i = 0; i < anchors.size() && i < sizes.size(); ++i) {
    const cv::Point a = anchors[i];
    const cv::Size sz = sizes[i];
    // Baseline 6 px above the point (upper) or the text's top 6 px below it
    // (lower); then stacked further up or down, one line at a time.
    std::vector<cv::Rect> options;
    for (int row = 0; row < 4; ++row) {
      const int up = a.y - 6 - sz.height - row * (sz.height + 4), down = a.y + 6 + row * (sz.height + 4);
      for (int x : {a.x + 8, a.x - 8 - sz.width}) {
        options.emplace_back(x, up, sz.width, sz.height);
        options.emplace_back(x, down, sz.width, sz.height);
      }
    }
    cv::Rect chosen = options[0];
    for (const cv::Rect& r : options)
      if (free_at(r)) {
        chosen = r;
        break;
      }
    placed.push_back(chosen);
  }
  return placed;
}

void WriteScatterPng(const ScatterChart& chart, const std::string& file) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", RenderScatter(chart), png)) throw Error(file, "PNG encoding failed");
  AtomicFile out(file);
  out.stream().write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.Commit();
}

}  // namespace hapcine::bench
