#include "datasets/plot_pages.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace hapcine {
namespace {

// A non-negative decimal number filling all of `text`, or NaN.
double ParseNonNegative(const std::string& text) {
  if (text.empty() || text[0] == '-' || text[0] == '+' || text[0] == ' ') return NAN;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return NAN;
  return v;
}

}  // namespace

double ParsePlotTime(const std::string& text, const std::string& option) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t colon; (colon = text.find(':', start)) != std::string::npos; start = colon + 1) {
    parts.push_back(text.substr(start, colon - start));
  }
  parts.push_back(text.substr(start));
  double seconds = 0;
  bool ok = parts.size() <= 3;
  for (size_t i = 0; ok && i < parts.size(); ++i) {
    const double v = ParseNonNegative(parts[i]);
    const bool last = i + 1 == parts.size();
    // Minutes and seconds after a colon stay under 60; only the last part has decimals.
    ok = std::isfinite(v) && (last || v == std::floor(v)) && (i == 0 || v < 60);
    seconds = seconds * 60 + v;
  }
  if (!ok) {
    throw UsageError(option + " '" + text +
                     "' is not a time (seconds like 90.5, or M:SS / H:MM:SS like 1:02:03.5)");
  }
  return seconds;
}

std::vector<TimeRange> PagesByDuration(double begin, double end, double page_s) {
  if (!(end > begin)) return {{begin, begin + 1}};
  if (!(page_s > 0)) return {{begin, end}};
  std::vector<TimeRange> pages;
  for (double at = begin; at < end;) {
    double next = at + page_s;
    if (end - next < 0.01 * page_s) next = end;
    pages.push_back({at, next});
    at = next;
  }
  return pages;
}

std::vector<TimeRange> PagesByShot(double begin, double end, const std::vector<double>& cuts) {
  std::vector<TimeRange> pages;
  double at = begin;
  for (double cut : cuts) {
    if (cut <= at || cut >= end) continue;
    pages.push_back({at, cut});
    at = cut;
  }
  pages.push_back({at, end > at ? end : at + 1});
  return pages;
}

std::string PagePath(const std::string& path, size_t index, size_t count) {
  if (count <= 1) return path;
  const size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = path.size();
  char number[16];
  std::snprintf(number, sizeof number, "-%03zu", index + 1);
  return path.substr(0, dot) + number + path.substr(dot);
}

}  // namespace hapcine
