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

// `v` clamped to [0, 1], and 0 when it is not finite (a confidence, a ratio).
inline double Clamp01(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0; }

}  // namespace hapcine
