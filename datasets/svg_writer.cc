#include "datasets/svg_writer.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"

namespace hapcine {
namespace {

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Rgb(const PlotColor& c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string F(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

void Text(std::ostream& o, double x, double y, const std::string& s, const char* anchor,
          int size = 12, const char* extra = "") {
  o << "<text x=\"" << F(x) << "\" y=\"" << F(y) << "\" font-size=\"" << size << "\" text-anchor=\""
    << anchor << "\"" << extra << ">" << Escape(s) << "</text>\n";
}

// The panel's series, clipped to its data area.
void WriteSeries(std::ostream& o, const PlotPanel& p, const FigureLayout& L, const PanelLayout& pl,
                 size_t pi) {
  const PlotRect& r = pl.plot;
  o << "<clipPath id=\"clip" << pi << "\"><rect x=\"" << F(r.x) << "\" y=\"" << F(r.y)
    << "\" width=\"" << F(r.w) << "\" height=\"" << F(r.h) << "\"/></clipPath>\n";
  o << "<g clip-path=\"url(#clip" << pi << ")\">\n";
  for (const auto& s : p.series) {
    for (const auto& run : SeriesRuns(s, L, r)) {
      if (s.filled && run.size() > 1) {  // the area down to y = 0
        o << "<polygon fill=\"" << Rgb(s.color)
          << "\" fill-opacity=\"0.3\" stroke=\"none\" points=\"";
        for (const auto& [x, y] : run) o << F(L.MapX(r, x)) << ',' << F(pl.MapY(y)) << ' ';
        o << F(L.MapX(r, run.back().first)) << ',' << F(pl.MapY(0)) << ' '
          << F(L.MapX(r, run.front().first)) << ',' << F(pl.MapY(0)) << "\"/>\n";
      }
      o << "<polyline fill=\"none\" stroke=\"" << Rgb(s.color) << "\" stroke-width=\"1.5\"";
      if (s.dashed) o << " stroke-dasharray=\"6,4\"";
      o << " points=\"";
      for (size_t i = 0; i < run.size(); ++i) {
        if (i) o << ' ';
        o << F(L.MapX(r, run[i].first)) << ',' << F(pl.MapY(run[i].second));
      }
      o << "\"/>\n";
    }
  }
}

void WriteLegend(std::ostream& o, const Figure& fig, const FigureLayout& L, size_t pi) {
  const PlotRect& r = L.panels[pi].plot;
  const std::vector<LegendEntry> entries = PanelLegend(fig, pi);
  const size_t rows = LegendRowsThatFit(r);
  double ly = r.y + 12;
  for (size_t i = 0; i < entries.size(); ++i, ly += kLegendRowPx) {
    if (i + 1 == rows && entries.size() > rows) {
      Text(o, L.legend_x + 30, ly, "+" + std::to_string(entries.size() - i) + " more", "start", 11);
      break;
    }
    const LegendEntry& e = entries[i];
    if (e.kind == LegendEntry::kSwatch) {
      o << "<rect x=\"" << F(L.legend_x) << "\" y=\"" << F(ly - 10)
        << "\" width=\"24\" height=\"10\" fill=\"" << Rgb(e.color) << "\"/>\n";
    } else if (e.kind == LegendEntry::kCut) {
      o << "<line x1=\"" << F(L.legend_x + 12) << "\" y1=\"" << F(ly - 11) << "\" x2=\""
        << F(L.legend_x + 12) << "\" y2=\"" << F(ly + 1) << "\" stroke=\"" << Rgb(e.color)
        << "\" stroke-width=\"2\"/>\n";
    } else {
      o << "<line x1=\"" << F(L.legend_x) << "\" y1=\"" << F(ly - 4) << "\" x2=\""
        << F(L.legend_x + 24) << "\" y2=\"" << F(ly - 4) << "\" stroke=\"" << Rgb(e.color)
        << "\" stroke-width=\"2\""
        << (e.kind == LegendEntry::kDashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    }
    Text(o, L.legend_x + 30, ly, e.name, "start", 11);
  }
}

// A panel's labelled bands (shots, effects), clipped to the plot.
void WriteBands(std::ostream& o, const PlotPanel& p, const FigureLayout& L, const PlotRect& r) {
  for (const auto& b : p.bands) {
    const double x0 = std::max(r.x, L.MapX(r, b.x_begin));
    const double x1 = std::min(r.x + r.w, L.MapX(r, b.x_end));
    if (!(x1 > x0)) continue;
    o << "<rect x=\"" << F(x0) << "\" y=\"" << F(r.y) << "\" width=\"" << F(x1 - x0)
      << "\" height=\"" << F(r.h) << "\" fill=\"" << Rgb(b.color)
      << "\" fill-opacity=\"0.35\" stroke=\"" << Rgb(b.color) << "\"/>\n";
    if (BandLabelFits(b.label, x1 - x0)) {
      Text(o, (x0 + x1) / 2, r.y + r.h / 2 + 4, b.label, "middle", 11);
    }
  }
}

// Grid lines with their tick labels, the plot's frame, title and y label.
void WriteGridAndFrame(std::ostream& o, const PlotPanel& p, const FigureLayout& L,
                       const PanelLayout& pl, double x_step) {
  const PlotRect& r = pl.plot;
  for (double t : L.x_ticks) {
    const double x = L.MapX(r, t);
    o << "<line x1=\"" << F(x) << "\" y1=\"" << F(r.y) << "\" x2=\"" << F(x) << "\" y2=\""
      << F(r.y + r.h) << "\" stroke=\"#e0e0e0\"/>\n";
    Text(o, x, r.y + r.h + 15, TickLabel(t, x_step), "middle", 11);
  }
  const double y_step = pl.y_ticks.size() > 1 ? pl.y_ticks[1] - pl.y_ticks[0] : 1.0;
  for (double t : pl.y_ticks) {
    const double y = pl.MapY(t);
    o << "<line x1=\"" << F(r.x) << "\" y1=\"" << F(y) << "\" x2=\"" << F(r.x + r.w) << "\" y2=\""
      << F(y) << "\" stroke=\"#e0e0e0\"/>\n";
    Text(o, r.x - 6, y + 4, TickLabel(t, y_step), "end", 11);
  }
  o << "<rect x=\"" << F(r.x) << "\" y=\"" << F(r.y) << "\" width=\"" << F(r.w) << "\" height=\""
    << F(r.h) << "\" fill=\"none\" stroke=\"black\"/>\n";
  if (!p.title.empty()) Text(o, r.x + r.w / 2, r.y - 7, p.title, "middle", 13);
  if (!p.y_label.empty()) Text(o, r.x - 6, r.y - 7, p.y_label, "end", 11);
}

// Shot boundaries inside the plot.
void WriteCutLines(std::ostream& o, const Figure& fig, const FigureLayout& L, const PlotRect& r) {
  for (double t : fig.cut_x) {
    const double x = L.MapX(r, t);
    if (x < r.x || x > r.x + r.w) continue;
    o << "<line x1=\"" << F(x) << "\" y1=\"" << F(r.y) << "\" x2=\"" << F(x) << "\" y2=\""
      << F(r.y + r.h) << "\" stroke=\"" << Rgb(CutLineColor()) << "\" stroke-width=\"2\"/>\n";
  }
}

}  // namespace

std::string RenderFigureSvg(const Figure& fig) {
  const FigureLayout L = LayoutFigure(fig);
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << L.width_px << "\" height=\""
    << L.height_px << "\" viewBox=\"0 0 " << L.width_px << " " << L.height_px
    << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  o << "<rect x=\"0\" y=\"0\" width=\"" << L.width_px << "\" height=\"" << L.height_px
    << "\" fill=\"white\"/>\n";
  if (!fig.title.empty())
    Text(o, L.width_px / 2.0, 22, fig.title, "middle", 16, " font-weight=\"bold\"");
  const double x_step = L.x_ticks.size() > 1 ? L.x_ticks[1] - L.x_ticks[0] : 1.0;

  for (size_t pi = 0; pi < fig.panels.size(); ++pi) {
    const PlotPanel& p = fig.panels[pi];
    const PanelLayout& pl = L.panels[pi];
    const PlotRect& r = pl.plot;
    o << "<g>\n";
    WriteBands(o, p, L, r);  // under everything else
    WriteGridAndFrame(o, p, L, pl, x_step);

    WriteSeries(o, p, L, pl, pi);
    o << "</g>\n";
    WriteCutLines(o, fig, L, r);  // over the curves
    WriteLegend(o, fig, L, pi);
    o << "</g>\n";
  }
  if (!fig.x_label.empty()) {
    const PlotRect& last = L.panels.back().plot;
    Text(o, last.x + last.w / 2, L.height_px - 6, fig.x_label, "middle", 12);
  }
  o << "</svg>\n";
  return o.str();
}

void WriteFigureSvgFile(const Figure& figure, const std::string& file) {
  const std::string svg = RenderFigureSvg(figure);
  AtomicFile out(file);
  out.stream() << svg;
  out.Commit();
}

}  // namespace hapcine
