#pragma once
// A plot described once, drawn twice: a Figure (panels stacked top to bottom,
// sharing the x axis) holds series (polylines) and bands (labelled x
// intervals, e.g. the haptic track's `effect` column). svg_writer.h renders it
// to SVG text, plot_png.h to an OpenCV image; both use the layout computed
// here, so the two outputs show the same thing at the same places.

#include <limits>
#include <string>
#include <vector>

namespace hapcine {

struct PlotColor {
  unsigned char r = 0, g = 0, b = 0;
};
// A palette of distinguishable colours (Tableau 10); index wraps.
PlotColor PaletteColor(int index);
// The colour of the shot-boundary lines: in no palette entry, so a cut never
// reads as a curve.
PlotColor CutLineColor();

struct PlotSeries {
  std::string name;       // legend entry; empty = no entry
  std::vector<double> x;  // same length as y; non-finite points break the line
  std::vector<double> y;
  PlotColor color;
  bool dashed = false;    // e.g. an estimate drawn over its ground truth
  bool filled = false;    // the area between the line and y = 0 shaded (a confidence band)
};

struct PlotBand {
  double x_begin = 0;
  double x_end = 0;
  std::string label;
  PlotColor color{200, 200, 200};
};

struct PlotPanel {
  std::string title;
  std::string y_label;     // units, drawn above the y axis
  std::vector<PlotSeries> series;
  std::vector<PlotBand> bands;
  double height_weight = 1.0;  // relative share of the figure height
  bool show_y_axis = true;     // false for a band-only time line
  // A fixed y range (both finite, y_min < y_max); NaN = from the data.
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
};

struct Figure {
  std::string title;
  std::string x_label = "time (s)";
  int width_px = 1200;
  int panel_height_px = 220;   // per unit of height_weight
  std::vector<PlotPanel> panels;
  // Shot boundaries: a vertical line in CutLineColor() across every panel,
  // and a "cut" entry in the first panel's legend.
  std::vector<double> cut_x;
  // The x range shown; NaN = the data's own.
  double x_from = std::numeric_limits<double>::quiet_NaN();
  double x_to = std::numeric_limits<double>::quiet_NaN();
};

// The part of `figure` inside [from, to] (from < to): series keep their
// points inside and one on either side (their lines reach the edges, drawn
// clipped), bands and cuts are cut to the range, and the x axis shows exactly
// [from, to]. Series x must be increasing (times). Cheap on long series: a
// two-hour 1 kHz track is cut into pages with a binary search each.
Figure CropFigure(const Figure& figure, double from, double to);


// ---- Layout shared by the renderers (pixels, y down) ----

struct PlotRect {
  double x = 0, y = 0, w = 0, h = 0;
};

struct PanelLayout {
  PlotRect plot;                 // the data area
  double y_min = 0, y_max = 1;   // data range shown
  std::vector<double> y_ticks;
  double MapY(double y) const { return plot.y + plot.h * (y_max - y) / (y_max - y_min); }
};

struct FigureLayout {
  int width_px = 0;
  int height_px = 0;
  double x_min = 0, x_max = 1;
  std::vector<double> x_ticks;
  double legend_x = 0;           // left edge of the legend column
  std::vector<PanelLayout> panels;
  // Same x mapping for every panel.
  double MapX(const PlotRect& r, double x) const { return r.x + r.w * (x - x_min) / (x_max - x_min); }
};

// Throws UsageError on an empty figure, mismatched x/y lengths or a size too
// small to draw in. Never returns a zero-width range (flat data is padded).
FigureLayout LayoutFigure(const Figure& figure);

// Whether a band's label fits inside the band drawn `width_px` wide (both
// renderers skip labels that would spill over their neighbours).
bool BandLabelFits(const std::string& label, double width_px);

// About `target` round tick values (1, 2, 5 x 10^k) covering [lo, hi].
std::vector<double> NiceTicks(double lo, double hi, int target = 6);
// Compact tick label ("0.25", "1e+03", "-5").
std::string TickLabel(double v, double step);

// The points of a series to draw, split into runs of finite points, with at
// most about 2 * max_columns points per run: above that, each pixel column
// keeps its first, min, max and last point (the visual envelope). Returns
// the runs in data coordinates.
std::vector<std::vector<std::pair<double, double>>> SeriesRuns(
    const PlotSeries& s, const FigureLayout& layout, const PlotRect& rect,
    size_t max_points = 8000);

// The legend entries of a panel: a name and colour per entry, each series
// with a name, then (band-only panels) each distinct band label once, then
// "cut" in the first panel of a figure with cuts in view.
struct LegendEntry {
  std::string name;
  PlotColor color;
  enum Kind { kLine, kDashed, kSwatch, kCut } kind = kLine;
};
std::vector<LegendEntry> PanelLegend(const Figure& figure, size_t panel);
// How many legend rows (kLegendRowPx apart, from 12 px under the top of the
// data area) fit beside a panel; the renderers end with "+N more" past that.
constexpr double kLegendRowPx = 16;
size_t LegendRowsThatFit(const PlotRect& plot);

}  // namespace hapcine
