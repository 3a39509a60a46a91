#include "core/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace hapcine {
namespace {

TEST(MedianTest, OddCountIsTheMiddleValue) {
  EXPECT_DOUBLE_EQ(Median({3, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(Median({5}), 5);
  EXPECT_DOUBLE_EQ(Median({-1, -1, 7, 7, -1}), -1);
}

TEST(MedianTest, EvenCountIsTheMeanOfTheTwoMiddleValues) {
  EXPECT_DOUBLE_EQ(Median({4, 1, 2, 3}), 2.5);
  EXPECT_DOUBLE_EQ(Median({2, 2}), 2);
  EXPECT_DOUBLE_EQ(Median({1e308, 1e308}), 1e308);  // no overflow in the mean
}

TEST(MedianTest, IgnoresNonFiniteValues) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(Median({NAN, 5}), 5);
  EXPECT_DOUBLE_EQ(Median({inf, -inf, 1, 3, NAN}), 2);
}

TEST(MedianTest, NoFiniteValueGivesTheFallback) {
  EXPECT_TRUE(std::isnan(Median({})));
  EXPECT_TRUE(std::isnan(Median({NAN, INFINITY})));
  EXPECT_DOUBLE_EQ(Median({}, 0.0), 0);
  EXPECT_DOUBLE_EQ(Median({NAN}, -1.0), -1);
}

// Against a full sort on random inputs with ties and both parities.
TEST(MedianTest, MatchesASortedReference) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(-20, 20), size(1, 40);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<double> v(size(rng));
    for (double& x : v) x = value(rng) * 0.5;
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    const double expected = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    EXPECT_DOUBLE_EQ(Median(v), expected) << "trial " << trial;
  }
}

TEST(QuantileTest, RankIsTheFloorOfQTimesTheCount) {
  const std::vector<double> v = {50, 10, 40, 20, 30};
  EXPECT_EQ(Quantile(v, 0.0), 10);
  EXPECT_EQ(Quantile(v, 0.25), 20);  // rank 1
  EXPECT_EQ(Quantile(v, 0.5), 30);
  EXPECT_EQ(Quantile(v, 0.99), 50);
  EXPECT_EQ(Quantile(v, 1.0), 50);  // rank n clamped to n - 1
}

TEST(QuantileTest, EvenCountGivesTheUpperMedianNotTheMean) {
  EXPECT_EQ(Quantile(std::vector<double>{4, 1, 2, 3}, 0.5), 3);
  EXPECT_DOUBLE_EQ(Median({4, 1, 2, 3}), 2.5);
  EXPECT_EQ(Quantile(std::vector<float>{2.5f, -1.f}, 0.5), 2.5f);  // any ordered type
}

TEST(QuantileTest, OneValueAndOutOfRangeFractions) {
  EXPECT_EQ(Quantile(std::vector<double>{7}, 0.5), 7);
  EXPECT_EQ(Quantile(std::vector<double>{3, 1, 2}, -1), 1);
  EXPECT_EQ(Quantile(std::vector<double>{3, 1, 2}, 2), 3);
  EXPECT_EQ(Quantile(std::vector<double>{3, 1, 2}, NAN), 1);  // NaN: the smallest
}

}  // namespace
TEST(Clamp01Test, ClampsAndMapsNonFiniteToZero) {
  EXPECT_EQ(Clamp01(0.25), 0.25);
  EXPECT_EQ(Clamp01(-1.0), 0.0);
  EXPECT_EQ(Clamp01(7.0), 1.0);
  EXPECT_EQ(Clamp01(std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(Clamp01(std::numeric_limits<double>::infinity()), 0.0);
}

}  // namespace hapcine
