#pragma once
// Synthetic frames for the tracker and shot-detector tests: smooth random
// textures (well-conditioned for KLT), warped by known motions, downscaled
// the way the FrameSource does (pixel edges scale).

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "extract/frame_source.h"

namespace hapcine::testing {

// Blurred noise at two scales (fine detail for KLT, coarse colour blotches
// so that the colour histogram is broad like a real picture's), shifted per
// channel by `tint` (-1..1 each: B, G, R) so that shots differ in colour.
inline cv::Mat NoiseTexture(cv::Size size, int seed, cv::Scalar tint = {0, 0, 0}) {
  cv::RNG rng(seed);
  auto noise = [&](double sigma) {
    cv::Mat m(size, CV_32F);
    rng.fill(m, cv::RNG::UNIFORM, 0, 255);
    cv::GaussianBlur(m, m, cv::Size(0, 0), sigma);
    cv::Scalar mean, stddev;
    cv::meanStdDev(m, mean, stddev);
    return cv::Mat((m - mean[0]) / stddev[0]);  // zero mean, unit std
  };
  const cv::Mat fine = noise(2.0), coarse = noise(20.0);
  cv::Mat channels[3];
  for (int c = 0; c < 3; ++c)
    channels[c] = 128 + 60 * tint[c] + 25 * fine + 20 * coarse + 25 * noise(30.0);
  cv::Mat bgr32, bgr;
  cv::merge(channels, 3, bgr32);
  bgr32.convertTo(bgr, CV_8UC3);
  return bgr;
}

// `a` on the left, `b` on the right (same size and type), blended linearly
// over columns [from, from + width): a picture whose colours change along a
// pan.
inline cv::Mat BlendedAcross(const cv::Mat& a, const cv::Mat& b, int from, int width) {
  cv::Mat out(a.size(), a.type());
  for (int x = 0; x < a.cols; ++x) {
    const double w = std::min(1.0, std::max(0.0, (x - from) / static_cast<double>(width)));
    cv::addWeighted(a.col(x), 1 - w, b.col(x), w, 0, out.col(x));
  }
  return out;
}

// Decoded-size view of `texture` under decoded_from_texture (2x3 affine),
// bicubic.
inline cv::Mat Warp(const cv::Mat& texture, const cv::Mat& decoded_from_texture, cv::Size decoded) {
  cv::Mat out;
  cv::warpAffine(texture, out, decoded_from_texture, decoded, cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return out;
}

// Translation only: pixel (x, y) of the result shows texture (x - dx, y - dy)
// shifted by the origin offset.
inline cv::Mat Shifted(const cv::Mat& texture, double dx, double dy, cv::Size decoded,
                       cv::Point2d origin = {100, 100}) {
  cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx - origin.x, 0, 1, dy - origin.y);
  return Warp(texture, m, decoded);
}

// A band-limited texture evaluated exactly at any sub-pixel position (sum of
// random plane waves, wavelengths 6..60 px), so that warped frames carry no
// interpolation error: value at decoded pixel (x, y) is T(texture_from_decoded
// (x, y)). `texture_from_decoded` is a 2x3 affine.
inline cv::Mat AnalyticTexture(cv::Size decoded, const cv::Mat& texture_from_decoded, int seed,
                               cv::Scalar tint = {1, 1, 1}) {
  cv::RNG rng(seed);
  const int waves = 24;
  std::vector<double> kx(waves), ky(waves), phase(waves), amp(waves);
  for (int k = 0; k < waves; ++k) {
    const double wavelength = rng.uniform(6.0, 60.0);
    const double dir = rng.uniform(0.0, 2 * M_PI);
    kx[k] = 2 * M_PI / wavelength * std::cos(dir);
    ky[k] = 2 * M_PI / wavelength * std::sin(dir);
    phase[k] = rng.uniform(0.0, 2 * M_PI);
    amp[k] = rng.uniform(0.5, 1.0);
  }
  double amp_sum = 0;
  for (double a : amp) amp_sum += a;
  const cv::Mat_<double> m = texture_from_decoded;
  cv::Mat out(decoded, CV_8UC3);
  for (int y = 0; y < decoded.height; ++y) {
    cv::Vec3b* row = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < decoded.width; ++x) {
      const double u = m(0, 0) * x + m(0, 1) * y + m(0, 2);
      const double v = m(1, 0) * x + m(1, 1) * y + m(1, 2);
      double s = 0;
      for (int k = 0; k < waves; ++k) s += amp[k] * std::sin(kx[k] * u + ky[k] * v + phase[k]);
      const double g = 128 + 100 * s / (0.35 * amp_sum);
      for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(g * tint[c]);
    }
  }
  return out;
}

// A FrameSource-like frame: decoded BGR image -> working gray/BGR at `scale`
// by area averaging.
inline Frame MakeFrame(const cv::Mat& decoded_bgr, int index, double scale = 1.0) {
  Frame f;
  f.index = index;
  f.time_s = index / 24.0;
  cv::Size work(static_cast<int>(std::lround(decoded_bgr.cols * scale)),
                static_cast<int>(std::lround(decoded_bgr.rows * scale)));
  if (work == decoded_bgr.size())
    f.bgr = decoded_bgr.clone();
  else
    cv::resize(decoded_bgr, f.bgr, work, 0, 0, cv::INTER_AREA);
  cv::cvtColor(f.bgr, f.gray, cv::COLOR_BGR2GRAY);
  f.scale = scale;
  f.decoded_width = decoded_bgr.cols;
  f.decoded_height = decoded_bgr.rows;
  return f;
}

}  // namespace hapcine::testing
