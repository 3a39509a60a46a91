#include "extract/vignetting.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"

namespace hapcine {

namespace {

// Brightness below this (8-bit) is dominated by grain, the black level and
// rounding, where a multiplicative field is not what changes it; above the
// other, clipping hides it.
constexpr float kDarkest = 16, kBrightest = 240;
constexpr int kFitIterations = 6;
constexpr double kHuber = 1.345;  // Huber's constant, in robust sigmas

// Bilinear read of an 8-bit picture; NaN outside it.
float Sample(const cv::Mat& image, float x, float y) {
  if (!(x >= 0 && y >= 0 && x <= image.cols - 1 && y <= image.rows - 1)) return NAN;
  const int x0 = std::min(static_cast<int>(x), image.cols - 2), y0 = std::min(static_cast<int>(y), image.rows - 2);
  if (x0 < 0 || y0 < 0) return NAN;
  const float fx = x - x0, fy = y - y0;
  const unsigned char* r0 = image.ptr<unsigned char>(y0);
  const unsigned char* r1 = image.ptr<unsigned char>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

// rho^2: squared distance from the picture's centre over the corner's.
double Rho2(const cv::Point2f& p, cv::Size size) {
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  const double corner2 = cx * cx + cy * cy;
  return ((p.x - cx) * (p.x - cx) + (p.y - cy) * (p.y - cy)) / std::max(corner2, 1.0);
}

struct Solved {
  double a = 0, b = 0;
  double var_corner = INFINITY;  // variance of a + b
};

// Weighted least squares of d_log - offset[step] on (d_rho2, d_rho4).
template <class Pairs>
Solved SolveWeighted(const Pairs& pairs, const std::vector<double>& offset, const std::vector<double>& weight,
                     double sigma) {
  double s22 = 0, s24 = 0, s44 = 0, t2 = 0, t4 = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double w = weight[i], u = pairs[i].d_rho2, v = pairs[i].d_rho4, y = pairs[i].d_log - offset[pairs[i].step];
    s22 += w * u * u;
    s24 += w * u * v;
    s44 += w * v * v;
    t2 += w * u * y;
    t4 += w * v * y;
  }
  Solved s;
  const double det = s22 * s44 - s24 * s24;
  if (!(det > 1e-12 * std::max(1.0, s22 * s44))) return s;
  s.a = (s44 * t2 - s24 * t4) / det;
  s.b = (s22 * t4 - s24 * t2) / det;
  // (X^T W X)^-1 scaled by the robust sigma: var a + var b + 2 cov.
  s.var_corner = sigma * sigma * (s44 + s22 - 2 * s24) / det;
  return s;
}

}  // namespace

double VignettingModel::corner_gain() const { return std::exp(a + b); }

void VignettingFit::AddStep(const cv::Mat& before, const cv::Mat& after, double scale,
                            const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                            cv::Size size) {
  const int step = steps_++;
  const float inv = static_cast<float>(1 / scale);
  for (size_t i = 0; i < from.size() && i < to.size() && !full(); ++i) {
    const double r1 = Rho2(from[i], size), r2 = Rho2(to[i], size);
    if (std::abs(r2 - r1) < kMinRadialMove) continue;
    const float v1 = Sample(before, from[i].x * inv, from[i].y * inv);
    const float v2 = Sample(after, to[i].x * inv, to[i].y * inv);
    if (!(v1 >= kDarkest && v2 >= kDarkest && v1 <= kBrightest && v2 <= kBrightest)) continue;
    pairs_.push_back({step, static_cast<float>(r2 - r1), static_cast<float>(r2 * r2 - r1 * r1),
                      std::log(v2 / v1)});
  }
}

// Alternates the per-step exposure offsets (the median of each step's
// residuals) and the field (Huber-weighted least squares).
VignettingModel VignettingFit::Decide(double min_falloff) const {
  VignettingModel m;
  if (pairs_.size() < kMinVignettingPairs) return m;
  std::vector<double> offset(steps_, 0.0), weight(pairs_.size(), 1.0);
  std::vector<std::vector<float>> by_step(steps_);
  std::vector<float> residual(pairs_.size());
  Solved s;
  double sigma = 1;
  for (int it = 0; it < kFitIterations; ++it) {
    for (auto& v : by_step) v.clear();
    for (const Pair& p : pairs_) by_step[p.step].push_back(p.d_log - s.a * p.d_rho2 - s.b * p.d_rho4);
    for (int k = 0; k < steps_; ++k) offset[k] = by_step[k].empty() ? 0 : Quantile(by_step[k], 0.5);
    std::vector<float> abs_residual(pairs_.size());
    for (size_t i = 0; i < pairs_.size(); ++i) {
      const Pair& p = pairs_[i];
      residual[i] = static_cast<float>(p.d_log - offset[p.step] - s.a * p.d_rho2 - s.b * p.d_rho4);
      abs_residual[i] = std::abs(residual[i]);
    }
    sigma = std::max(1.4826 * Quantile(std::move(abs_residual), 0.5), 1e-6);
    for (size_t i = 0; i < pairs_.size(); ++i)
      weight[i] = std::abs(residual[i]) <= kHuber * sigma ? 1.0 : kHuber * sigma / std::abs(residual[i]);
    s = SolveWeighted(pairs_, offset, weight, sigma);
  }
  m.a = s.a;
  m.b = s.b;
  // A lens only loses light off its axis (cos^4 law, the barrel's shade):
  // a brighter corner is the scene, not the lens. A correction of a field
  // taken may go either way.
  const double corner = s.a + s.b;
  const bool darker = corner <= std::log(1 - min_falloff);
  const bool refinement = min_falloff < kMinCornerFalloff && std::abs(corner) >= -std::log(1 - min_falloff);
  m.found = (darker || refinement) && std::isfinite(s.var_corner) &&
            std::abs(corner) >= kMinFalloffSigmas * std::sqrt(s.var_corner);
  return m;
}

cv::Mat FlatFieldGain(const VignettingModel& model, cv::Size size) {
  cv::Mat gain(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    float* row = gain.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const double r2 = Rho2(cv::Point2f(static_cast<float>(x), static_cast<float>(y)), size);
      row[x] = static_cast<float>(-(model.a * r2 + model.b * r2 * r2));  // log of 1 / V
    }
  }
  double lo = 0, hi = 0;
  cv::minMaxLoc(gain, &lo, &hi);
  gain -= hi;
  cv::exp(gain, gain);
  return gain;
}

cv::Mat FlatFielded(const cv::Mat& gray, const cv::Mat& gain) {
  cv::Mat f, out;
  gray.convertTo(f, CV_32F);
  cv::multiply(f, gain, f);
  f.convertTo(out, CV_8U);
  return out;
}

}  // namespace hapcine
