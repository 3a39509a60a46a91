#include "haptics/random_model.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

// Direct form II transposed biquad, RBJ low-pass with Q = 1/sqrt(2).
void BiquadInPlace(std::vector<double>* x, double b0, double b1, double b2, double a1, double a2) {
  double z1 = 0, z2 = 0;
  for (double& v : *x) {
    const double in = v;
    const double out = b0 * in + z1;
    z1 = b1 * in - a1 * out + z2;
    z2 = b2 * in - a2 * out;
    v = out;
  }
}

}  // namespace

void RandomOptions::Check() const {
  if (!(cutoff_hz > 0 && cutoff_hz <= 50)) throw UsageError("random cutoff must be in (0, 50] Hz");
  if (!(fade_s >= 0 && fade_s <= 60)) throw UsageError("random fade must be in [0, 60] s");
}

double ZeroPhaseSectionCutoffHz(double cutoff_hz, double rate_hz) {
  // A bilinear 2nd-order Butterworth with cutoff f0 has
  // |H(f)|^2 = 1 / (1 + (tan(pi f / fs) / tan(pi f0 / fs))^4). Run forward and
  // backward the response is |H|^2, which is 1/sqrt(2) (-3 dB) at fc when
  // (tan(pi fc / fs) / tan(pi f0 / fs))^4 = sqrt(2) - 1.
  const double ratio = std::pow(std::sqrt(2.0) - 1, 0.25);
  return rate_hz / kPi * std::atan(std::tan(kPi * cutoff_hz / rate_hz) / ratio);
}

std::vector<double> ButterworthLowPassZeroPhase(const std::vector<double>& x, double cutoff_hz,
                                                double rate_hz) {
  const double w0 = 2 * kPi * ZeroPhaseSectionCutoffHz(cutoff_hz, rate_hz) / rate_hz;
  const double alpha = std::sin(w0) / (2 * (1 / std::sqrt(2.0)));
  const double c = std::cos(w0);
  const double a0 = 1 + alpha;
  const double b0 = (1 - c) / 2 / a0, b1 = (1 - c) / a0, b2 = (1 - c) / 2 / a0;
  const double a1 = -2 * c / a0, a2 = (1 - alpha) / a0;
  std::vector<double> y = x;
  BiquadInPlace(&y, b0, b1, b2, a1, a2);
  std::reverse(y.begin(), y.end());
  BiquadInPlace(&y, b0, b1, b2, a1, a2);
  std::reverse(y.begin(), y.end());
  return y;
}

std::vector<ActuatorFrame> RandomFrames(size_t n, double rate_hz, const SeatGeometry& seat,
                                        const RandomOptions& o) {
  std::vector<ActuatorFrame> out(n);
  for (auto& f : out)
    for (auto& v : f) v.setZero();
  if (n == 0) return out;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> channel(n);
  double peak = 0;
  for (int a = 0; a < kNumActuators; ++a) {
    for (int k = 0; k < 3; ++k) {
      for (double& v : channel) v = normal(rng);
      const std::vector<double> lp = ButterworthLowPassZeroPhase(channel, o.cutoff_hz, rate_hz);
      for (size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / rate_hz;
        const double t_end = static_cast<double>(n - 1 - i) / rate_hz;
        const double fade = o.fade_s > 0 ? SmootherStep(std::min(t, t_end) / o.fade_s) : 1.0;
        out[i][a][k] = lp[i] * fade;
        peak = std::max(peak, std::abs(out[i][a][k]));
      }
    }
  }
  if (peak > 0) {
    const double gain = seat.usable_half_m / peak;
    for (auto& f : out)
      for (auto& v : f) v *= gain;
  }
  return out;
}

}  // namespace hapcine
