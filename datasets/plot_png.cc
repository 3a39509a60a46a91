#include "datasets/plot_png.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine {
namespace {

cv::Scalar Bgr(const PlotColor& c) { return cv::Scalar(c.b, c.g, c.r); }

const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(224, 224, 224);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// anchor: 0 left, 1 centre, 2 right; y is the baseline.
void PutText(cv::Mat& img, const std::string& s, double x, double y, int anchor,
             double scale = 0.4, int thickness = 1) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(s, kFont, scale, thickness, &base);
  const double dx = anchor == 0 ? 0 : anchor == 1 ? -sz.width / 2.0 : -sz.width;
  cv::putText(img, s, cv::Point(static_cast<int>(std::lround(x + dx)), static_cast<int>(std::lround(y))),
              kFont, scale, kBlack, thickness, cv::LINE_AA);
}

cv::Point2d P(double x, double y) { return {x, y}; }

// Sub-pixel anti-aliased line (4 bits of fractional precision).
void Line(cv::Mat& img, cv::Point2d a, cv::Point2d b, const cv::Scalar& color, int thickness) {
  constexpr int kShift = 4;
  constexpr double kScale = 1 << kShift;
  cv::line(img, cv::Point(static_cast<int>(std::lround(a.x * kScale)), static_cast<int>(std::lround(a.y * kScale))),
           cv::Point(static_cast<int>(std::lround(b.x * kScale)), static_cast<int>(std::lround(b.y * kScale))),
           color, thickness, cv::LINE_AA, kShift);
}

// A polyline with an optional 6-on/4-off dash pattern that continues across
// vertices (the same pattern the SVG uses).
void Polyline(cv::Mat& img, const std::vector<cv::Point2d>& pts, const cv::Scalar& color,
              bool dashed) {
  if (pts.size() == 1) {
    Line(img, pts[0], pts[0], color, 2);
    return;
  }
  double phase = 0;  // distance into the current 10 px period
  for (size_t i = 1; i < pts.size(); ++i) {
    const cv::Point2d a = pts[i - 1], b = pts[i];
    if (!dashed) {
      Line(img, a, b, color, 1);
      continue;
    }
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    double pos = 0;
    while (pos < len) {
      const bool on = phase < 6;
      const double step = std::min(len - pos, on ? 6 - phase : 10 - phase);
      if (on && step > 0) {
        const cv::Point2d p0 = a + (b - a) * (pos / len);
        const cv::Point2d p1 = a + (b - a) * ((pos + step) / len);
        Line(img, p0, p1, color, 1);
      }
      pos += step;
      phase += step;
      if (phase >= 10 - 1e-9) phase = 0;
      if (step <= 0) break;
    }
  }
}

// The area between a run and y = 0, blended over the data area.
void FillUnder(cv::Mat& area, const std::vector<cv::Point2d>& pts, double zero_y,
               const cv::Scalar& color) {
  if (pts.size() < 2) return;
  std::vector<cv::Point> poly;
  for (const cv::Point2d& p : pts) poly.emplace_back(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  poly.emplace_back(poly.back().x, static_cast<int>(std::lround(zero_y)));
  poly.emplace_back(poly.front().x, static_cast<int>(std::lround(zero_y)));
  cv::Mat shade = area.clone();
  cv::fillPoly(shade, std::vector<std::vector<cv::Point>>{poly}, color);
  cv::addWeighted(shade, 0.3, area, 0.7, 0, area);
}

// Shot boundaries: solid, not anti-aliased, so their colour stays exact.
void DrawCuts(cv::Mat& img, const Figure& fig, const FigureLayout& L, const PlotRect& r) {
  for (double t : fig.cut_x) {
    const int x = static_cast<int>(std::lround(L.MapX(r, t)));
    if (x < r.x || x > r.x + r.w) continue;
    cv::line(img, cv::Point(x, static_cast<int>(r.y) + 1), cv::Point(x, static_cast<int>(r.y + r.h) - 1),
             Bgr(CutLineColor()), 2, cv::LINE_8);
  }
}

void DrawLegend(cv::Mat& img, const Figure& fig, const FigureLayout& L, size_t pi) {
  const PlotRect& r = L.panels[pi].plot;
  const std::vector<LegendEntry> entries = PanelLegend(fig, pi);
  const size_t rows = LegendRowsThatFit(r);
  double ly = r.y + 12;
  for (size_t i = 0; i < entries.size(); ++i, ly += kLegendRowPx) {
    if (i + 1 == rows && entries.size() > rows) {
      PutText(img, "+" + std::to_string(entries.size() - i) + " more", L.legend_x + 30, ly, 0, 0.38);
      break;
    }
    const LegendEntry& e = entries[i];
    if (e.kind == LegendEntry::kSwatch) {
      cv::rectangle(img, cv::Point(static_cast<int>(L.legend_x), static_cast<int>(ly - 10)),
                    cv::Point(static_cast<int>(L.legend_x + 24), static_cast<int>(ly)), Bgr(e.color), cv::FILLED);
    } else if (e.kind == LegendEntry::kCut) {
      cv::line(img, cv::Point(static_cast<int>(L.legend_x + 12), static_cast<int>(ly - 11)),
               cv::Point(static_cast<int>(L.legend_x + 12), static_cast<int>(ly + 1)), Bgr(e.color), 2, cv::LINE_8);
    } else {
      Polyline(img, {P(L.legend_x, ly - 4), P(L.legend_x + 24, ly - 4)}, Bgr(e.color),
               e.kind == LegendEntry::kDashed);
    }
    PutText(img, e.name, L.legend_x + 30, ly, 0, 0.38);
  }
}

}  // namespace

cv::Mat RenderFigurePng(const Figure& fig) {
  const FigureLayout L = LayoutFigure(fig);
  cv::Mat img(L.height_px, L.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  if (!fig.title.empty()) PutText(img, fig.title, L.width_px / 2.0, 22, 1, 0.6, 1);
  const double x_step = L.x_ticks.size() > 1 ? L.x_ticks[1] - L.x_ticks[0] : 1.0;

  for (size_t pi = 0; pi < fig.panels.size(); ++pi) {
    const PlotPanel& p = fig.panels[pi];
    const PanelLayout& pl = L.panels[pi];
    const PlotRect& r = pl.plot;
    const cv::Rect clip(static_cast<int>(r.x), static_cast<int>(r.y), static_cast<int>(r.w) + 1,
                        static_cast<int>(r.h) + 1);
    for (const auto& b : p.bands) {
      const double x0 = std::max(r.x, L.MapX(r, b.x_begin));
      const double x1 = std::min(r.x + r.w, L.MapX(r, b.x_end));
      if (!(x1 > x0)) continue;
      cv::Mat roi = img(cv::Rect(static_cast<int>(x0), static_cast<int>(r.y),
                                 std::max(1, static_cast<int>(x1 - x0)), static_cast<int>(r.h)));
      cv::Mat fill(roi.size(), roi.type(), Bgr(b.color));
      cv::addWeighted(fill, 0.35, roi, 0.65, 0, roi);
      cv::rectangle(img, cv::Point(static_cast<int>(x0), static_cast<int>(r.y)),
                    cv::Point(static_cast<int>(x1), static_cast<int>(r.y + r.h)), Bgr(b.color), 1);
      if (BandLabelFits(b.label, x1 - x0)) {
        PutText(img, b.label, (x0 + x1) / 2, r.y + r.h / 2 + 4, 1, 0.35);
      }
    }
    for (double t : L.x_ticks) {
      const double x = L.MapX(r, t);
      Line(img, P(x, r.y), P(x, r.y + r.h), kGrid, 1);
      PutText(img, TickLabel(t, x_step), x, r.y + r.h + 15, 1, 0.35);
    }
    const double y_step = pl.y_ticks.size() > 1 ? pl.y_ticks[1] - pl.y_ticks[0] : 1.0;
    for (double t : pl.y_ticks) {
      const double y = pl.MapY(t);
      Line(img, P(r.x, y), P(r.x + r.w, y), kGrid, 1);
      PutText(img, TickLabel(t, y_step), r.x - 6, y + 4, 2, 0.35);
    }
    cv::rectangle(img, cv::Point(static_cast<int>(r.x), static_cast<int>(r.y)),
                  cv::Point(static_cast<int>(r.x + r.w), static_cast<int>(r.y + r.h)), kBlack, 1);
    if (!p.title.empty()) PutText(img, p.title, r.x + r.w / 2, r.y - 7, 1, 0.45);
    if (!p.y_label.empty()) PutText(img, p.y_label, r.x - 6, r.y - 7, 2, 0.35);

    // Draw the series into a copy of the data area so nothing leaks outside.
    cv::Mat area = img(clip).clone();
    for (const auto& s : p.series) {
      for (const auto& run : SeriesRuns(s, L, r, 1u << 30)) {
        std::vector<cv::Point2d> pts;
        pts.reserve(run.size());
        for (const auto& [x, y] : run) pts.push_back(P(L.MapX(r, x) - clip.x, pl.MapY(y) - clip.y));
        if (s.filled) FillUnder(area, pts, pl.MapY(0) - clip.y, Bgr(s.color));
        Polyline(area, pts, Bgr(s.color), s.dashed);
      }
    }
    area.copyTo(img(clip));
    DrawCuts(img, fig, L, r);
    cv::rectangle(img, clip.tl(), clip.br() - cv::Point(1, 1), kBlack, 1);
    DrawLegend(img, fig, L, pi);
  }
  if (!fig.x_label.empty()) {
    const PlotRect& last = L.panels.back().plot;
    PutText(img, fig.x_label, last.x + last.w / 2, L.height_px - 6, 1, 0.42);
  }
  return img;
}

std::vector<unsigned char> EncodeFigurePng(const Figure& figure, const std::string& name) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", RenderFigurePng(figure), png)) throw Error(name, "PNG encoding failed");
  return png;
}

void WriteFigurePngFile(const Figure& figure, const std::string& file) {
  const std::vector<unsigned char> png = EncodeFigurePng(figure, file);
  AtomicFile out(file);
  out.stream().write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.Commit();
}

}  // namespace hapcine
