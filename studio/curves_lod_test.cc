#include "studio/curves_lod.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace hapcine::studio {
namespace {

// Irregular times (a gap, jitter) and values with spikes.
CurveGroup RandomGroup(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(0.005, 0.02), value(-1, 1);
  CurveGroup g;
  std::vector<float> v;
  double t = 0;
  for (size_t i = 0; i < n; ++i) {
    t += step(rng) + (i == n / 2 ? 3.0 : 0.0);
    g.time_s.push_back(t);
    v.push_back(static_cast<float>(value(rng) * (i % 97 == 0 ? 50 : 1)));
  }
  g.names = {"v"};
  g.series.emplace_back(v);
  return g;
}

TEST(CurvesLod, BucketsBoundEveryRawSampleAndAverageIt) {
  const CurveGroup g = RandomGroup(5000, 1);
  for (const auto& [from, to, points] : std::vector<std::tuple<double, double, int>>{
           {0, 100, 300}, {g.time_s[17], g.time_s[4000], 777}, {10.0, 10.5, 7}, {0, 100, 20000}}) {
    const CurveBuckets b = QueryCurves({&g}, from, to, points);
    ASSERT_EQ(b.names.size(), 1u);
    const size_t n = b.centre_s.size();
    ASSERT_GE(n, 1u);
    ASSERT_LE(n, static_cast<size_t>(points));
    const double width = (to - from) / n;
    std::vector<double> sum(n, 0), count(n, 0);
    for (size_t i = 0; i < g.time_s.size(); ++i) {
      const double t = g.time_s[i];
      if (t < from || t > to) continue;
      const size_t j = std::min(n - 1, static_cast<size_t>((t - from) / width));
      const float v = g.series[0].value(i);
      EXPECT_LE(b.values[0].min[j], v) << "bucket " << j;
      EXPECT_GE(b.values[0].max[j], v) << "bucket " << j;
      sum[j] += v;
      count[j] += 1;
    }
    for (size_t j = 0; j < n; ++j) {
      if (count[j] > 0) {
        EXPECT_NEAR(b.values[0].mean[j], sum[j] / count[j], 1e-3) << "bucket " << j;
      }
    }
  }
}

TEST(CurvesLod, NoMoreBucketsThanSamplesAndEmptyBucketsInterpolate) {
  CurveGroup g;
  g.time_s = {0, 1, 2};
  g.names = {"v"};
  g.series.emplace_back(std::vector<float>{0, 10, 20});
  const CurveBuckets few = QueryCurves({&g}, 0, 2, 1000);
  EXPECT_EQ(few.centre_s.size(), 3u);
  // Between samples: one bucket without a sample gets the line through them.
  const CurveBuckets inside = QueryCurves({&g}, 0.4, 0.6, 100);
  ASSERT_EQ(inside.centre_s.size(), 1u);
  EXPECT_NEAR(inside.values[0].mean[0], 5.0, 1e-5);
  EXPECT_EQ(inside.values[0].min[0], inside.values[0].max[0]);
  // A single instant, and a range past the end (clamped to the last value).
  EXPECT_EQ(QueryCurves({&g}, 1, 1, 10).values[0].max[0], 10.0f);
  EXPECT_EQ(QueryCurves({&g}, 5, 6, 10).values[0].mean[0], 20.0f);
}

TEST(CurvesLod, EmptyAndNonFiniteSeriesStayDefined) {
  CurveGroup empty;
  empty.names = {"e"};
  empty.series.emplace_back(std::vector<float>{});
  CurveGroup bad;
  bad.time_s = {0, 1};
  bad.names = {"b"};
  bad.series.emplace_back(std::vector<float>{NAN, INFINITY});
  const CurveBuckets b = QueryCurves({&empty, &bad}, 0, 1, 4);
  ASSERT_EQ(b.names.size(), 2u);
  for (const BucketValues& v : b.values) {
    for (float x : v.mean) EXPECT_TRUE(std::isfinite(x));
  }
  const std::string json = CurveBucketsToJson(b);
  EXPECT_EQ(json.find("nan"), std::string::npos);
  EXPECT_EQ(json.find("inf"), std::string::npos);
}

TEST(CurvesLod, JsonHasTheContractsShape) {
  CurveGroup g;
  g.time_s = {0, 0.5, 1};
  g.names = {"pan"};
  g.series.emplace_back(std::vector<float>{1.5f, -2, 0.25f});
  const std::string json = CurveBucketsToJson(QueryCurves({&g}, 0, 1, 3));
  EXPECT_NE(json.find("\"series\":{\"pan\":{\"min\":[1.5,-2,0.25]"), std::string::npos) << json;
  EXPECT_EQ(json.rfind("{\"from\":0,\"to\":1,\"t\":[", 0), 0u) << json;
}

}  // namespace
}  // namespace hapcine::studio
