#include "core/statistics.h"

#include <algorithm>
#include <cmath>

namespace hapcine {

double Median(std::vector<double> values, double if_none) {
  values.erase(std::remove_if(values.begin(), values.end(),
                              [](double x) { return !std::isfinite(x); }),
               values.end());
  if (values.empty()) return if_none;
  const size_t n = values.size();
  const auto mid = values.begin() + n / 2;
  std::nth_element(values.begin(), mid, values.end());
  if (n % 2) return *mid;
  // Even count: the lower middle value is the largest of the lower half,
  // which nth_element left (unordered) before `mid`. Halves first: the sum
  // of two huge values would overflow.
  return 0.5 * *std::max_element(values.begin(), mid) + 0.5 * *mid;
}

}  // namespace hapcine
