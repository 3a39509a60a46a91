#include "datasets/plot_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"

namespace hapcine {
namespace {

// Pixel margins around the data areas.
constexpr double kTitleH = 34;       // figure title
constexpr double kPanelTitleH = 22;  // panel title / y label line
constexpr double kAxisH = 22;        // x tick labels under every panel
constexpr double kXLabelH = 22;      // x axis label under the last panel
constexpr double kLeftW = 72;        // y tick labels
constexpr double kLegendW = 150;     // legend column on the right (at least)
constexpr double kLegendCharW = 7.5; // legend text width per character (both renderers)

void PadRange(double* lo, double* hi) {
  if (!(*hi > *lo)) {
    const double mid = std::isfinite(*lo) ? *lo : 0.0;
    const double half = std::max(1e-9, std::abs(mid) * 0.1) + (mid == 0 ? 1.0 : 0.0);
    *lo = mid - half;
    *hi = mid + half;
    return;
  }
  const double pad = 0.05 * (*hi - *lo);
  *lo -= pad;
  *hi += pad;
}

}  // namespace

PlotColor PaletteColor(int index) {
  static const PlotColor kPalette[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},
                                       {214, 39, 40},  {148, 103, 189}, {140, 86, 75},
                                       {227, 119, 194}, {127, 127, 127}, {188, 189, 34},
                                       {23, 190, 207}};
  const int n = sizeof(kPalette) / sizeof(kPalette[0]);
  return kPalette[((index % n) + n) % n];
}

bool BandLabelFits(const std::string& label, double width_px) {
  return !label.empty() && 6.5 * static_cast<double>(label.size()) + 4 <= width_px;
}

std::vector<double> NiceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || target < 1) return ticks;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  const double first = std::ceil(lo / step - 1e-9) * step;
  for (double v = first; v <= hi + 1e-9 * step; v += step) {
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
    if (ticks.size() > 100) break;
  }
  return ticks;
}

std::string TickLabel(double v, double step) {
  char buf[32];
  const double a = std::max(std::abs(v), std::abs(step));
  if (a >= 1e5 || (a > 0 && a < 1e-3)) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  } else {
    const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), v);
  }
  std::string s = buf;
  if (s == "-0") s = "0";
  return s;
}

FigureLayout LayoutFigure(const Figure& fig) {
  if (fig.panels.empty()) throw UsageError("figure has no panels");
  if (fig.width_px < 300 || fig.panel_height_px < 60) {
    throw UsageError("figure too small to draw (width >= 300, panel height >= 60 px)");
  }
  FigureLayout L;
  L.width_px = fig.width_px;
  double x_lo = std::numeric_limits<double>::infinity();
  double x_hi = -x_lo;
  for (const auto& p : fig.panels) {
    if (!(p.height_weight > 0)) throw UsageError("panel height weight must be > 0");
    for (const auto& s : p.series) {
      if (s.x.size() != s.y.size()) throw UsageError("series '" + s.name + "': x and y differ in length");
      for (double x : s.x) {
        if (std::isfinite(x)) {
          x_lo = std::min(x_lo, x);
          x_hi = std::max(x_hi, x);
        }
      }
    }
    for (const auto& b : p.bands) {
      for (double x : {b.x_begin, b.x_end}) {
        if (std::isfinite(x)) {
          x_lo = std::min(x_lo, x);
          x_hi = std::max(x_hi, x);
        }
      }
    }
  }
  if (!std::isfinite(x_lo)) {
    x_lo = 0;
    x_hi = 1;
  } else if (!(x_hi > x_lo)) {
    PadRange(&x_lo, &x_hi);
  }
  L.x_min = x_lo;
  L.x_max = x_hi;
  L.x_ticks = NiceTicks(x_lo, x_hi, 8);
  // The legend column widens for long names, up to a third of the figure.
  size_t longest = 0;
  for (const auto& p : fig.panels)
    for (const auto& ser : p.series) longest = std::max(longest, ser.name.size());
  const double legend_w =
      std::min(std::max(kLegendW, 40 + kLegendCharW * static_cast<double>(longest)),
               std::max(kLegendW, fig.width_px / 3.0));
  L.legend_x = fig.width_px - legend_w + 10;

  double y = kTitleH;
  for (const auto& p : fig.panels) {
    PanelLayout pl;
    pl.plot.x = kLeftW;
    pl.plot.w = fig.width_px - kLeftW - legend_w;
    pl.plot.y = y + kPanelTitleH;
    pl.plot.h = p.height_weight * fig.panel_height_px - kPanelTitleH - kAxisH;
    if (pl.plot.h < 10) pl.plot.h = 10;
    y = pl.plot.y + pl.plot.h + kAxisH;
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const auto& s : p.series) {
      for (double v : s.y) {
        if (std::isfinite(v)) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      }
    }
    if (!std::isfinite(lo)) {
      lo = 0;
      hi = 1;
    } else {
      PadRange(&lo, &hi);
    }
    pl.y_min = lo;
    pl.y_max = hi;
    if (p.show_y_axis) pl.y_ticks = NiceTicks(lo, hi, std::max(2, static_cast<int>(pl.plot.h / 35)));
    L.panels.push_back(pl);
  }
  L.height_px = static_cast<int>(std::ceil(y + kXLabelH));
  return L;
}

std::vector<std::vector<std::pair<double, double>>> SeriesRuns(const PlotSeries& s,
                                                               const FigureLayout& layout,
                                                               const PlotRect& rect,
                                                               size_t max_points) {
  std::vector<std::vector<std::pair<double, double>>> runs;
  std::vector<std::pair<double, double>> run;
  auto flush = [&]() {
    if (run.empty()) return;
    if (run.size() > max_points) {
      // Keep first/min/max/last of each pixel column: the drawn envelope is
      // unchanged, the file stays small (a 1 kHz track of 10 minutes has
      // 600 000 samples).
      std::vector<std::pair<double, double>> kept;
      size_t i = 0;
      while (i < run.size()) {
        const long col = std::lround(layout.MapX(rect, run[i].first));
        size_t j = i, lo = i, hi = i;
        while (j < run.size() && std::lround(layout.MapX(rect, run[j].first)) == col) {
          if (run[j].second < run[lo].second) lo = j;
          if (run[j].second > run[hi].second) hi = j;
          ++j;
        }
        std::vector<size_t> idx = {i, lo, hi, j - 1};
        std::sort(idx.begin(), idx.end());
        idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
        for (size_t k : idx) kept.push_back(run[k]);
        i = j;
      }
      run.swap(kept);
    }
    runs.push_back(std::move(run));
    run.clear();
  };
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
      run.emplace_back(s.x[i], s.y[i]);
    } else {
      flush();
    }
  }
  flush();
  return runs;
}

}  // namespace hapcine
