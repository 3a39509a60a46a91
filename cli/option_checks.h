#pragma once
// Ranges of the numeric options, checked by CLI11 while parsing: a value out
// of range, NaN or infinite is a usage error (exit 2) before any work, and the
// range shows in --help beside the option's type ("FLOAT:in [0, 1000]").
// CLI::Range alone lets NaN through (every comparison with NaN is false).

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace hapcine::cli {

// Bounds as a reader writes them: integers in full, others as %g.
inline std::string RangeBound(double v) {
  char buf[32];
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return buf;
}

// A finite number in [lo, hi]. For integer options the type conversion that
// follows refuses fractions, so the same validator serves both.
class FiniteRange : public CLI::Validator {
 public:
  FiniteRange(double lo, double hi) {
    const std::string range = "[" + RangeBound(lo) + ", " + RangeBound(hi) + "]";
    description("in " + range);
    func_ = [lo, hi, range](std::string& text) -> std::string {
      const char* begin = text.c_str();
      char* end = nullptr;
      const double v = std::strtod(begin, &end);
      if (text.empty() || end != begin + text.size()) return "'" + text + "' is not a number";
      if (!std::isfinite(v)) return "'" + text + "' is not a finite number";
      if (v < lo || v > hi) return text + " is outside " + range;
      return std::string();
    };
  }
};

}  // namespace hapcine::cli
