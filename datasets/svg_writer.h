#pragma once
// A Figure (plot_figure.h) as a standalone SVG document, written by hand: no
// plotting library. Axes, ticks, grid, polylines (dashed when asked), bands
// with labels, and a legend per panel. Long series are reduced to their
// per-pixel envelope (SeriesRuns), so files stay small.

#include <string>

#include "datasets/plot_figure.h"

namespace hapcine {

std::string RenderFigureSvg(const Figure& figure);
// Atomic (temporary file, then rename).
void WriteFigureSvgFile(const Figure& figure, const std::string& file);

}  // namespace hapcine
