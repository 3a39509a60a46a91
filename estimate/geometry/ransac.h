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

namespace ransac_internal {

// A model's inliers (squared residual within thr2) and truncated cost;
// `res`: scratch for the residuals.
template <typename Estimator>
void Score(const std::vector<typename Estimator::X_t>& X, const std::vector<typename Estimator::Y_t>& Y,
           const typename Estimator::M_t& model, double thr2, std::vector<double>* res, int* inliers, double* cost) {
  Estimator::Residuals(X, Y, model, res);
  *inliers = 0;
  *cost = 0;
  for (double r : *res) {
    if (std::isfinite(r) && r <= thr2) {
      ++*inliers;
      *cost += r;
    } else {
      *cost += thr2;
    }
  }
}

// Trials needed to draw an all-inlier sample of k with `confidence`, at an
// inlier share of inliers / n, within the options' bounds.
inline int TrialsNeeded(int inliers, int n, int k, const RansacOptions& options, int max_trials) {
  const double w = static_cast<double>(inliers) / n;
  const double p_good = std::pow(w, k);
  if (p_good >= 1.0) return std::min(max_trials, options.min_trials);
  if (p_good > 1e-12) {
    const double needed = std::log(1 - options.confidence) / std::log(1 - p_good);
    return std::clamp(static_cast<int>(std::ceil(needed)), options.min_trials, options.max_trials);
  }
  return max_trials;
}

template <typename M>
struct Best {
  int inliers = -1;
  double cost = std::numeric_limits<double>::infinity();
  M model{};
  // Takes `model` if it has more inliers, or as many at a lower cost.
  bool Offer(const M& m, int inl, double c) {
    if (!(inl > inliers || (inl == inliers && c < cost))) return false;
    inliers = inl;
    cost = c;
    model = m;
    return true;
  }
};

// Least squares on the best model's inliers, kept while it does not lose
// inliers (local optimisation).
template <typename Estimator>
void RefitOnInliers(const std::vector<typename Estimator::X_t>& X, const std::vector<typename Estimator::Y_t>& Y,
                    double thr2, const RansacOptions& options, std::vector<double>* res,
                    Best<typename Estimator::M_t>* best) {
  const int n = static_cast<int>(X.size());
  for (int it = 0; it < options.local_refits; ++it) {
    Estimator::Residuals(X, Y, best->model, res);
    std::vector<typename Estimator::X_t> xi;
    std::vector<typename Estimator::Y_t> yi;
    for (int i = 0; i < n; ++i) {
      if (std::isfinite((*res)[i]) && (*res)[i] <= thr2) {
        xi.push_back(X[i]);
        yi.push_back(Y[i]);
      }
    }
    if (static_cast<int>(xi.size()) <= Estimator::kMinNumSamples) break;
    bool improved = false;
    for (const auto& model : Estimator::Estimate(xi, yi)) {
      int inl;
      double cost;
      Score<Estimator>(X, Y, model, thr2, res, &inl, &cost);
      const int before_inliers = best->inliers;
      const double before_cost = best->cost;
      if (best->Offer(model, inl, cost)) improved = inl > before_inliers || cost < before_cost * (1 - 1e-9);
    }
    if (!improved) break;
  }
}

}  // namespace ransac_internal

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
  std::mt19937 rng(options.seed);
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  std::vector<typename Estimator::X_t> xs(k);
  std::vector<typename Estimator::Y_t> ys(k);
  ransac_internal::Best<M> best;
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
      ransac_internal::Score<Estimator>(X, Y, model, thr2, &res, &inl, &cost);
      if (best.Offer(model, inl, cost)) max_trials = ransac_internal::TrialsNeeded(inl, n, k, options, max_trials);
    }
  }
  report.num_trials = trial;
  if (best.inliers < k) return report;
  ransac_internal::RefitOnInliers<Estimator>(X, Y, thr2, options, &res, &best);
  Estimator::Residuals(X, Y, best.model, &res);
  report.inlier_mask.assign(n, 0);
  report.num_inliers = 0;
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(res[i]) && res[i] <= thr2) {
      report.inlier_mask[i] = 1;
      ++report.num_inliers;
    }
  }
  report.model = best.model;
  report.success = report.num_inliers >= k;
  return report;
}

}  // namespace hapcine
