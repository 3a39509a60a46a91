#pragma once
// A Figure (plot_figure.h) drawn with OpenCV (cv::line, cv::putText) into a
// BGR image, and written as PNG. Same layout as the SVG renderer.

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "datasets/plot_figure.h"

namespace hapcine {

cv::Mat RenderFigurePng(const Figure& figure);  // CV_8UC3
// The PNG file's bytes; throws Error(name, ...) when encoding fails.
std::vector<unsigned char> EncodeFigurePng(const Figure& figure, const std::string& name);
// Encodes to PNG in memory, then writes atomically. Throws Error on failure.
void WriteFigurePngFile(const Figure& figure, const std::string& file);

}  // namespace hapcine
