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

// The x range every panel shares: the figure's own, else the data's.
void XRange(const Figure& fig, double* lo, double* hi) {
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
  if (std::isfinite(fig.x_from) && std::isfinite(fig.x_to) && fig.x_to > fig.x_from) {
    x_lo = fig.x_from;
    x_hi = fig.x_to;
  } else if (!std::isfinite(x_lo)) {
    x_lo = 0;
    x_hi = 1;
  } else if (!(x_hi > x_lo)) {
    PadRange(&x_lo, &x_hi);
  }
  *lo = x_lo;
  *hi = x_hi;
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

PlotColor CutLineColor() { return PlotColor{200, 0, 110}; }

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
  double x_lo = 0, x_hi = 1;
  XRange(fig, &x_lo, &x_hi);
  L.x_min = x_lo;
  L.x_max = x_hi;
  L.x_ticks = NiceTicks(x_lo, x_hi, 8);
  // The legend column widens for long names, up to a third of the figure.
  size_t longest = 0;
  for (size_t i = 0; i < fig.panels.size(); ++i)
    for (const LegendEntry& e : PanelLegend(fig, i)) longest = std::max(longest, e.name.size());
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
      if (s.filled && std::isfinite(lo)) {  // the shaded area reaches y = 0
        lo = std::min(lo, 0.0);
        hi = std::max(hi, 0.0);
      }
    }
    if (std::isfinite(p.y_min) && std::isfinite(p.y_max) && p.y_max > p.y_min) {
      lo = p.y_min - 0.05 * (p.y_max - p.y_min);
      hi = p.y_max + 0.05 * (p.y_max - p.y_min);
    } else if (!std::isfinite(lo)) {
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

namespace {

// Indices [begin, end) of the points of increasing `x` to keep for [from, to]:
// those inside and one on either side.
std::pair<size_t, size_t> KeptRange(const std::vector<double>& x, double from, double to) {
  size_t begin = static_cast<size_t>(std::lower_bound(x.begin(), x.end(), from) - x.begin());
  size_t end = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), to) - x.begin());
  if (begin > 0) --begin;
  if (end < x.size()) ++end;
  return {begin, std::max(begin, end)};
}

PlotSeries CropSeries(const PlotSeries& s, double from, double to) {
  PlotSeries out = s;
  out.x.clear();
  out.y.clear();
  if (std::is_sorted(s.x.begin(), s.x.end())) {
    const auto [begin, end] = KeptRange(s.x, from, to);
    out.x.assign(s.x.begin() + static_cast<long>(begin), s.x.begin() + static_cast<long>(end));
    out.y.assign(s.y.begin() + static_cast<long>(begin), s.y.begin() + static_cast<long>(end));
    return out;
  }
  for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {  // rare: not a time series
    if (s.x[i] >= from && s.x[i] <= to) {
      out.x.push_back(s.x[i]);
      out.y.push_back(s.y[i]);
    }
  }
  return out;
}

}  // namespace

Figure CropFigure(const Figure& fig, double from, double to) {
  if (!(from < to)) throw UsageError("plot range: the start must come before the end");
  Figure out;
  out.title = fig.title;
  out.x_label = fig.x_label;
  out.width_px = fig.width_px;
  out.panel_height_px = fig.panel_height_px;
  out.x_from = from;
  out.x_to = to;
  for (const PlotPanel& p : fig.panels) {
    PlotPanel q = p;
    q.series.clear();
    q.bands.clear();
    for (const PlotSeries& s : p.series) q.series.push_back(CropSeries(s, from, to));
    for (PlotBand b : p.bands) {
      b.x_begin = std::max(b.x_begin, from);
      b.x_end = std::min(b.x_end, to);
      if (b.x_end > b.x_begin) q.bands.push_back(b);
    }
    out.panels.push_back(std::move(q));
  }
  for (double x : fig.cut_x) {
    if (x >= from && x <= to) out.cut_x.push_back(x);
  }
  return out;
}

std::vector<LegendEntry> PanelLegend(const Figure& fig, size_t panel) {
  std::vector<LegendEntry> entries;
  const PlotPanel& p = fig.panels.at(panel);
  for (const PlotSeries& s : p.series) {
    if (!s.name.empty()) {
      entries.push_back({s.name, s.color, s.dashed ? LegendEntry::kDashed : LegendEntry::kLine});
    }
  }
  if (p.series.empty()) {  // a time line: its colours name the labels
    std::vector<std::string> seen;
    for (const PlotBand& b : p.bands) {
      if (b.label.empty() || std::find(seen.begin(), seen.end(), b.label) != seen.end()) continue;
      seen.push_back(b.label);
      entries.push_back({b.label, b.color, LegendEntry::kSwatch});
    }
  }
  if (panel == 0 && !fig.cut_x.empty()) entries.push_back({"cut", CutLineColor(), LegendEntry::kCut});
  return entries;
}

size_t LegendRowsThatFit(const PlotRect& plot) {
  // The column runs from the top of the data area to the x tick labels.
  return static_cast<size_t>(std::max(1.0, std::floor((plot.h + 8) / kLegendRowPx)));
}

}  // namespace hapcine
