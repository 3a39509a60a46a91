#include "studio/curves_lod.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace hapcine::studio {
namespace {

constexpr size_t kFanOut = 4;  // samples (or blocks) per block of the next level

// Linear interpolation of series `s` of `g` at time t, clamped to the ends.
float InterpolateAt(const CurveGroup& g, size_t s, double t) {
  const std::vector<double>& time = g.time_s;
  if (time.empty()) return 0.0f;
  const size_t hi = std::lower_bound(time.begin(), time.end(), t) - time.begin();
  if (hi == 0) return g.series[s].value(0);
  if (hi == time.size()) return g.series[s].value(time.size() - 1);
  const double span = time[hi] - time[hi - 1];
  const double u = span > 0 ? (t - time[hi - 1]) / span : 1.0;
  const float a = g.series[s].value(hi - 1), b = g.series[s].value(hi);
  return static_cast<float>(a + u * (b - a));
}

// Index range [first, last) of the samples with lo <= t < hi (t <= hi when closed).
std::pair<size_t, size_t> SampleRange(const std::vector<double>& time, double lo, double hi,
                                      bool closed) {
  const size_t first = std::lower_bound(time.begin(), time.end(), lo) - time.begin();
  const auto end = closed ? std::upper_bound(time.begin(), time.end(), hi)
                          : std::lower_bound(time.begin(), time.end(), hi);
  return {first, std::max(first, static_cast<size_t>(end - time.begin()))};
}

void AppendNumber(std::string* out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, std::isfinite(v) ? v : 0.0);
  out->append(buf, r.ptr);
}

void AppendFloat(std::string* out, float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, std::isfinite(v) ? v : 0.0f);
  out->append(buf, r.ptr);
}

template <typename T>
void AppendArray(std::string* out, const std::vector<T>& values) {
  out->push_back('[');
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) out->push_back(',');
    if constexpr (std::is_same_v<T, float>) {
      AppendFloat(out, values[i]);
    } else {
      AppendNumber(out, values[i]);
    }
  }
  out->push_back(']');
}

// The JSON text of a series name: names are the server's own identifiers.
void AppendName(std::string* out, const std::string& name) {
  out->push_back('"');
  out->append(name);
  out->push_back('"');
}

}  // namespace

CurvePyramid::CurvePyramid(std::vector<float> values) : values_(std::move(values)) {
  for (float& v : values_) {
    if (!std::isfinite(v)) v = 0.0f;
  }
  std::vector<Block> level;
  for (size_t i = 0; i + kFanOut <= values_.size(); i += kFanOut) {
    Block b{values_[i], values_[i], 0.0f};
    double sum = 0;
    for (size_t k = 0; k < kFanOut; ++k) {
      b.min = std::min(b.min, values_[i + k]);
      b.max = std::max(b.max, values_[i + k]);
      sum += values_[i + k];
    }
    b.mean = static_cast<float>(sum / kFanOut);
    level.push_back(b);
  }
  while (level.size() >= 1) {
    levels_.push_back(level);
    std::vector<Block> next;
    const std::vector<Block>& below = levels_.back();
    for (size_t i = 0; i + kFanOut <= below.size(); i += kFanOut) {
      Block b = below[i];
      double sum = 0;
      for (size_t k = 0; k < kFanOut; ++k) {
        b.min = std::min(b.min, below[i + k].min);
        b.max = std::max(b.max, below[i + k].max);
        sum += below[i + k].mean;
      }
      b.mean = static_cast<float>(sum / kFanOut);
      next.push_back(b);
    }
    if (next.empty()) break;
    level = std::move(next);
  }
}

// Greedy cover of [first, last) by the largest aligned blocks that fit:
// at most 2 * (kFanOut - 1) pieces per level.
void CurvePyramid::Aggregate(size_t first, size_t last, float* min, float* max,
                             double* mean) const {
  float lo = values_[first], hi = values_[first];
  double sum = 0;
  size_t i = first;
  while (i < last) {
    int level = -1;
    size_t block = 1;
    for (size_t k = 0, b = kFanOut; k < levels_.size() && i % b == 0 && i + b <= last;
         ++k, b *= kFanOut) {
      level = static_cast<int>(k);
      block = b;
    }
    if (level < 0) {
      lo = std::min(lo, values_[i]);
      hi = std::max(hi, values_[i]);
      sum += values_[i];
    } else {
      const Block& b = levels_[level][i / block];
      lo = std::min(lo, b.min);
      hi = std::max(hi, b.max);
      sum += static_cast<double>(b.mean) * block;
    }
    i += block;
  }
  *min = lo;
  *max = hi;
  *mean = sum / static_cast<double>(last - first);
}

CurveBuckets QueryCurves(const std::vector<const CurveGroup*>& groups, double from_s, double to_s,
                         int max_buckets) {
  CurveBuckets out;
  out.from_s = from_s;
  out.to_s = std::max(from_s, to_s);
  size_t densest = 0;
  for (const CurveGroup* g : groups) {
    const auto [first, last] = SampleRange(g->time_s, out.from_s, out.to_s, true);
    densest = std::max(densest, last - first);
  }
  const size_t n = std::clamp<size_t>(densest, 1, static_cast<size_t>(std::max(1, max_buckets)));
  const double width = (out.to_s - out.from_s) / static_cast<double>(n);
  for (size_t j = 0; j < n; ++j) out.centre_s.push_back(out.from_s + (j + 0.5) * width);
  for (const CurveGroup* g : groups) {
    std::vector<std::pair<size_t, size_t>> ranges(n);
    for (size_t j = 0; j < n; ++j) {
      const double lo = out.from_s + j * width;
      const double hi = j + 1 == n ? out.to_s : out.from_s + (j + 1) * width;
      ranges[j] = SampleRange(g->time_s, lo, hi, j + 1 == n);
    }
    for (size_t s = 0; s < g->names.size(); ++s) {
      out.names.push_back(g->names[s]);
      BucketValues v;
      v.min.resize(n);
      v.max.resize(n);
      v.mean.resize(n);
      for (size_t j = 0; j < n; ++j) {
        const auto [first, last] = ranges[j];
        if (first < last) {
          double mean = 0;
          g->series[s].Aggregate(first, last, &v.min[j], &v.max[j], &mean);
          v.mean[j] = static_cast<float>(mean);
        } else {
          v.min[j] = v.max[j] = v.mean[j] = InterpolateAt(*g, s, out.centre_s[j]);
        }
      }
      out.values.push_back(std::move(v));
    }
  }
  return out;
}

std::string CurveBucketsToJson(const CurveBuckets& b) {
  std::string out = "{\"from\":";
  AppendNumber(&out, b.from_s);
  out += ",\"to\":";
  AppendNumber(&out, b.to_s);
  out += ",\"t\":";
  AppendArray(&out, b.centre_s);
  out += ",\"series\":{";
  for (size_t s = 0; s < b.names.size(); ++s) {
    if (s) out.push_back(',');
    AppendName(&out, b.names[s]);
    out += ":{\"min\":";
    AppendArray(&out, b.values[s].min);
    out += ",\"max\":";
    AppendArray(&out, b.values[s].max);
    out += ",\"mean\":";
    AppendArray(&out, b.values[s].mean);
    out.push_back('}');
  }
  out += "}}";
  return out;
}

}  // namespace hapcine::studio
