#include "extract/affine_lk.h"

#include <cmath>
#include <vector>

namespace hapcine {

namespace {

// Bilinear sample of a CV_8UC1 image; false outside [0, size - 1].
bool Sample(const cv::Mat& image, float x, float y, float* value) {
  if (!(x >= 0 && y >= 0 && x <= image.cols - 1 && y <= image.rows - 1)) return false;
  const int x0 = std::min(static_cast<int>(x), image.cols - 2), y0 = std::min(static_cast<int>(y), image.rows - 2);
  const float fx = x - x0, fy = y - y0;
  const uchar* r0 = image.ptr<uchar>(y0);
  const uchar* r1 = image.ptr<uchar>(y0 + 1);
  *value = (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
  return true;
}

// The image under the warp, on a (2 h + 3)^2 grid of anchor offsets (one
// more ring than the patch for the central differences).
bool SampleWarped(const cv::Mat& image, cv::Point2f position, const cv::Matx22f& linear, int h,
                  std::vector<float>* values) {
  const int side = 2 * h + 3;
  values->resize(static_cast<size_t>(side) * side);
  for (int v = -h - 1; v <= h + 1; ++v)
    for (int u = -h - 1; u <= h + 1; ++u) {
      const float x = position.x + linear(0, 0) * u + linear(0, 1) * v;
      const float y = position.y + linear(1, 0) * u + linear(1, 1) * v;
      if (!Sample(image, x, y, &(*values)[(v + h + 1) * side + (u + h + 1)])) return false;
    }
  return true;
}

// One Gauss-Newton step: the update of (translation in anchor offsets,
// linear part, gain, bias) that best explains warped - (gain T + bias);
// returns the residual's RMS before the step, or -1 if singular.
double Step(const std::vector<float>& warped, const std::vector<float>& patch, int h, double gain, double bias,
            cv::Vec<double, 8>* delta) {
  const int side = 2 * h + 3;
  cv::Matx<double, 8, 8> normal = cv::Matx<double, 8, 8>::zeros();
  cv::Vec<double, 8> rhs = cv::Vec<double, 8>::all(0);
  double sum_r2 = 0;
  size_t k = 0;
  for (int v = -h; v <= h; ++v)
    for (int u = -h; u <= h; ++u, ++k) {
      const int at = (v + h + 1) * side + (u + h + 1);
      const double gx = 0.5 * (warped[at + 1] - warped[at - 1]), gy = 0.5 * (warped[at + side] - warped[at - side]);
      const double r = warped[at] - (gain * patch[k] + bias);
      const cv::Vec<double, 8> j(gx, gy, gx * u, gx * v, gy * u, gy * v, -patch[k], -1.0);
      for (int a = 0; a < 8; ++a) {
        rhs[a] -= j[a] * r;
        for (int b = a; b < 8; ++b) normal(a, b) += j[a] * j[b];
      }
      sum_r2 += r * r;
    }
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < a; ++b) normal(a, b) = normal(b, a);
  if (!cv::solve(normal, rhs, *delta, cv::DECOMP_CHOLESKY)) return -1;
  return std::sqrt(sum_r2 / static_cast<double>(patch.size()));
}

}  // namespace

AffinePatchFit AlignAffinePatch(const cv::Mat& anchor_image, cv::Point2f anchor, const cv::Mat& image,
                                const AffinePatchFit& start, int half_window, int max_iterations,
                                float min_step_px) {
  const int h = half_window;
  AffinePatchFit fit = start;
  fit.ok = false;
  fit.inside = true;
  std::vector<float> patch, warped;
  patch.reserve(static_cast<size_t>(2 * h + 1) * (2 * h + 1));
  double mean = 0;
  for (int v = -h; v <= h; ++v)
    for (int u = -h; u <= h; ++u) {
      float value = 0;
      if (!Sample(anchor_image, anchor.x + u, anchor.y + v, &value)) {
        fit.inside = false;
        return fit;
      }
      patch.push_back(value);
      mean += value;
    }
  mean /= static_cast<double>(patch.size());
  double contrast = 0;
  for (float p : patch) contrast += (p - mean) * (p - mean);
  contrast = std::sqrt(contrast / static_cast<double>(patch.size()));
  if (!(contrast > 0)) return fit;
  double gain = 1, bias = 0, rms = 0;
  for (int it = 0; it < max_iterations; ++it) {
    if (!SampleWarped(image, fit.position, fit.linear, h, &warped)) {
      fit.inside = false;
      return fit;
    }
    cv::Vec<double, 8> d;
    rms = Step(warped, patch, h, gain, bias, &d);
    if (rms < 0 || !std::isfinite(d[0])) return fit;
    // Compose: W(W_delta(u)) = position + L (delta_t + (I + delta_L) u).
    const cv::Matx22f dl(1 + float(d[2]), float(d[3]), float(d[4]), 1 + float(d[5]));
    const cv::Point2f step(fit.linear(0, 0) * float(d[0]) + fit.linear(0, 1) * float(d[1]),
                           fit.linear(1, 0) * float(d[0]) + fit.linear(1, 1) * float(d[1]));
    fit.position += step;
    fit.linear = fit.linear * dl;
    gain += d[6];
    bias += d[7];
    if (std::hypot(step.x, step.y) < min_step_px) break;
  }
  if (!SampleWarped(image, fit.position, fit.linear, h, &warped)) {
    fit.inside = false;
    return fit;
  }
  cv::Vec<double, 8> unused;
  rms = Step(warped, patch, h, gain, bias, &unused);
  // In units of the matched patch's contrast (gain x the anchor's): a fit
  // that flattens the patch (gain -> 0) explains nothing. A warp that folds
  // the patch (det <= 0) or shrinks or grows its area by more than 4x has
  // lost the window's detail.
  const double det = cv::determinant(fit.linear);
  fit.residual = static_cast<float>(rms / (gain * contrast));
  fit.ok = rms >= 0 && gain > 0 && det > 0.25 && det < 4;
  return fit;
}

}  // namespace hapcine
