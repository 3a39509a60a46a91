#pragma once
// One generic RANSAC for every two-view estimator (COLMAP's "estimator
// concept"). An Estimator provides
//   using X_t, Y_t, M_t;                    // sample and model types
//   static constexpr int kMinNumSamples;    // minimal sample size
//   static std::vector<M_t> Estimate(const std::vector<X_t>&, const std::vector<Y_t>&);
//       // minimal (n == kMinNumSamples) or least-squares (n > kMinNumSamples)
//       // solutions; empty on degenerate input, never NaN
//   static void Residuals(const std::vector<X_t>&, const std::vector<Y_t>&, const M_t&,
//                         std::vector<double>* squared_residuals);
// Ransac() samples minimal sets, scores by inlier count (ties: lower truncated
// squared error), stops adaptively at `confidence`, and re-fits the best model
// on its inliers (local optimisation) while that helps.

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/error.h"

namespace hapcine {

struct RansacOptions {
  double max_error = 1e-3;    // inlier threshold on the residual (not squared), data units
  double confidence = 0.999;  // stop when an all-inlier sample was drawn with this probability
  int min_trials = 20;
  int max_trials = 1000;
  int local_refits = 3;       // least-squares re-fits on the inliers of the best model
  unsigned seed = 1234;       // deterministic by default
  void Check() const {
    if (!(max_error > 0) || !std::isfinite(max_error)) throw UsageError("RANSAC max_error must be > 0");
    if (!(confidence > 0 && confidence < 1)) throw UsageError("RANSAC confidence must be in (0, 1)");
    if (min_trials < 1 || max_trials < min_trials) throw UsageError("RANSAC needs 1 <= min_trials <= max_trials");
    if (local_refits < 0) throw UsageError("RANSAC local_refits must be >= 0");
  }
};

template <typename Model>
struct RansacReport {
  bool success = false;
  int num_trials = 0;
  int num_inliers = 0;
  std::vector<char> inlier_mask;
  Model model{};
};

template <typename Estimator>
RansacReport<typename Estimator::M_t> Ransac(const std::vector<typename Estimator::X_t>& X,
                                             const std::vector<typename Estimator::Y_t>& Y,
                                             const RansacOptions& options) {
  using M = typename Estimator::M_t;
  RansacReport<M> report;
  const int n = static_cast<int>(X.size());
  const int k = Estimator::kMinNumSamples;
  if (n != static_cast<int>(Y.size()) || n < k) return report;
  const double thr2 = options.max_error * options.max_error;

  std::vector<double> res;
  auto score = [&](const M& model, int* inliers, double* cost) {
    Estimator::Residuals(X, Y, model, &res);
    *inliers = 0;
    *cost = 0;
    for (double r : res) {
      if (std::isfinite(r) && r <= thr2) {
        ++*inliers;
        *cost += r;
      } else {
        *cost += thr2;
      }
    }
  };

  std::mt19937 rng(options.seed);
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  std::vector<typename Estimator::X_t> xs(k);
  std::vector<typename Estimator::Y_t> ys(k);
  int best_inliers = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  M best{};
  int max_trials = options.max_trials;
  int trial = 0;
  for (; trial < max_trials; ++trial) {
    for (int i = 0; i < k; ++i) {  // partial Fisher-Yates: k distinct indices
      std::uniform_int_distribution<int> d(i, n - 1);
      std::swap(idx[i], idx[d(rng)]);
      xs[i] = X[idx[i]];
      ys[i] = Y[idx[i]];
    }
    for (const M& model : Estimator::Estimate(xs, ys)) {
      int inl;
      double cost;
      score(model, &inl, &cost);
      if (inl > best_inliers || (inl == best_inliers && cost < best_cost)) {
        best_inliers = inl;
        best_cost = cost;
        best = model;
        const double w = static_cast<double>(inl) / n;
        const double p_good = std::pow(w, k);
        if (p_good >= 1.0) {
          max_trials = std::min(max_trials, options.min_trials);
        } else if (p_good > 1e-12) {
          const double needed = std::log(1 - options.confidence) / std::log(1 - p_good);
          max_trials = std::clamp(static_cast<int>(std::ceil(needed)), options.min_trials,
                                  options.max_trials);
        }
      }
    }
  }
  report.num_trials = trial;
  if (best_inliers < k) return report;

  // Local optimisation: least squares on the inliers, kept while it does not lose inliers.
  for (int it = 0; it < options.local_refits; ++it) {
    Estimator::Residuals(X, Y, best, &res);
    std::vector<typename Estimator::X_t> xi;
    std::vector<typename Estimator::Y_t> yi;
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(res[i]) && res[i] <= thr2) {
        xi.push_back(X[i]);
        yi.push_back(Y[i]);
      }
    }
    if (static_cast<int>(xi.size()) <= k) break;
    bool improved = false;
    for (const M& model : Estimator::Estimate(xi, yi)) {
      int inl;
      double cost;
      score(model, &inl, &cost);
      if (inl > best_inliers || (inl == best_inliers && cost < best_cost)) {
        improved = inl > best_inliers || cost < best_cost * (1 - 1e-9);
        best_inliers = inl;
        best_cost = cost;
        best = model;
      }
    }
    if (!improved) break;
  }

  Estimator::Residuals(X, Y, best, &res);
  report.inlier_mask.assign(n, 0);
  report.num_inliers = 0;
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(res[i]) && res[i] <= thr2) {
      report.inlier_mask[i] = 1;
      ++report.num_inliers;
    }
  }
  report.model = best;
  report.success = report.num_inliers >= k;
  return report;
}

}  // namespace hapcine
