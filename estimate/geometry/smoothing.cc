#include "estimate/geometry/smoothing.h"

#include <algorithm>
#include <cmath>

namespace hapcine {
namespace {

// Radius min(3 sigma, i, n - 1 - i), compared in double: 3 sigma can exceed
// any int (sigma 1e10 or inf), and a sigma whose square underflows is a delta.
int Radius(int i, int n, double sigma) {
  const int edge = std::min(i, n - 1 - i);
  if (!(sigma * sigma > 0)) return 0;
  const double reach = std::ceil(3 * sigma);
  return reach < edge ? static_cast<int>(reach) : edge;
}

// Symmetric weights for sample i of n over Radius(i, n, sigma).
std::vector<double> Weights(int i, int n, double sigma, int* radius) {
  const int r = Radius(i, n, sigma);
  *radius = r;
  if (r == 0) return {1.0};  // also keeps 0 / 0 out when sigma^2 underflows
  std::vector<double> w(2 * r + 1);
  double sum = 0;
  for (int k = -r; k <= r; ++k) sum += w[k + r] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (double& v : w) v /= sum;
  return w;
}

template <typename T>
std::vector<T> SmoothLinear(const std::vector<T>& x, double sigma, const T& zero) {
  if (!(sigma > 0) || x.size() < 3) return x;
  const int n = static_cast<int>(x.size());
  std::vector<T> y(n);
  for (int i = 0; i < n; ++i) {
    int r;
    const auto w = Weights(i, n, sigma, &r);
    T acc = zero;
    for (int k = -r; k <= r; ++k) acc += w[k + r] * x[i + k];
    y[i] = acc;
  }
  return y;
}

}  // namespace

Eigen::Vector3d LogRotation(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-12) return 2 * q.vec();
  const double angle = 2 * std::atan2(s, q.w());
  return q.vec() * (angle / s);
}

Eigen::Quaterniond ExpRotation(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

std::vector<double> SmoothScalars(const std::vector<double>& x, double sigma) {
  return SmoothLinear<double>(x, sigma, 0.0);
}

std::vector<Eigen::Vector3d> SmoothVectors(const std::vector<Eigen::Vector3d>& x, double sigma) {
  return SmoothLinear<Eigen::Vector3d>(x, sigma, Eigen::Vector3d::Zero());
}

std::vector<Eigen::Quaterniond> SmoothRotations(const std::vector<Eigen::Quaterniond>& q,
                                                double sigma) {
  if (!(sigma > 0) || q.size() < 3) return q;
  const int n = static_cast<int>(q.size());
  std::vector<Eigen::Quaterniond> y(n);
  for (int i = 0; i < n; ++i) {
    int r;
    const auto w = Weights(i, n, sigma, &r);
    const Eigen::Quaterniond qi_inv = q[i].normalized().conjugate();
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (int k = -r; k <= r; ++k) acc += w[k + r] * LogRotation(qi_inv * q[i + k].normalized());
    y[i] = (q[i].normalized() * ExpRotation(acc)).normalized();
  }
  return y;
}

}  // namespace hapcine
