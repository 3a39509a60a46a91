#pragma once
// Small statistics shared by the stages.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hapcine {

// Median of the finite values of `values` (NaN and +-inf are ignored): the
// middle value, or the mean of the two middle values for an even count.
// `if_none` when no finite value is left: NaN by default; callers that use
// the median as a scale in further arithmetic pass their own fallback.
// O(n) (selection, not a full sort); takes the vector by value to reorder it.
double Median(std::vector<double> values,
              double if_none = std::numeric_limits<double>::quiet_NaN());

// The value of rank floor(q * n) of the n `values` (q clamped to [0, 1],
// rank at most n - 1): one of the values, never an interpolation. q = 0.5
// is the upper median (for an even count, the larger middle value, where
// Median() averages the two). O(n) selection; `values` must not be empty.
template <typename T>
T Quantile(std::vector<T> values, double q) {
  const double fraction = q > 0 ? std::min(q, 1.0) : 0.0;  // NaN: 0
  const size_t rank = std::min(values.size() - 1, static_cast<size_t>(fraction * values.size()));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[rank];
}

// `v` clamped to [0, 1], and 0 when it is not finite (a confidence, a ratio).
inline double Clamp01(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0; }

}  // namespace hapcine
