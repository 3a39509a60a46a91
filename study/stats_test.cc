#include "study/stats.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hapcine::study {
namespace {

TEST(NormalTest, KnownValues) {
  EXPECT_NEAR(NormalCdf(0), 0.5, 1e-16);
  EXPECT_NEAR(NormalCdf(1.96), 0.9750021048517795, 1e-14);
  EXPECT_NEAR(NormalQuantile(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(NormalQuantile(0.5), 0, 1e-15);
  // Deep tails keep relative precision (both branches of Acklam's split).
  EXPECT_NEAR(NormalQuantile(1e-10), -6.361340902404056, 1e-9);
  for (double p : {1e-300, 1e-12, 0.001, 0.02425, 0.3, 0.7, 0.99, 1 - 1e-12}) {
    const double x = NormalQuantile(p);
    const double back = p < 0.5 ? NormalCdf(x) : 1 - NormalSf(x);
    EXPECT_NEAR(back / p, 1, 1e-9) << p;
  }
  EXPECT_TRUE(std::isinf(NormalQuantile(0)));
  EXPECT_TRUE(std::isinf(NormalQuantile(1)));
  EXPECT_TRUE(std::isinf(NormalQuantile(std::nan(""))));
}

TEST(ChiSquareTest, KnownValues) {
  // 3.841458820694124 is the 95% point of chi-square(1).
  EXPECT_NEAR(ChiSquareSf(3.841458820694124, 1), 0.05, 1e-12);
  // df = 2 is an exponential: P(X >= x) = exp(-x/2).
  for (double x : {0.1, 1.0, 11.142857142857142, 60.0})
    EXPECT_NEAR(ChiSquareSf(x, 2) / std::exp(-x / 2), 1, 1e-12) << x;
  EXPECT_EQ(ChiSquareSf(0, 3), 1);
  EXPECT_EQ(ChiSquareSf(-1, 3), 1);
  EXPECT_GE(ChiSquareSf(1e5, 3), 0);
  // P + Q = 1 on both sides of the series / continued-fraction switch.
  for (double a : {0.5, 1.5, 10.0})
    for (double x : {0.2, a + 0.9, a + 1.1, 30.0})
      EXPECT_NEAR(GammaP(a, x) + GammaQ(a, x), 1, 1e-14);
}

TEST(HolmTest, PAdjustExample) {
  // p.adjust(c(0.01,0.02,0.03,0.04,0.05), "holm"), by hand (m = 5):
  // 5*.01=.05, 4*.02=.08, 3*.03=.09, 2*.04=.08 -> cummax .09, 1*.05 -> .09.
  const auto adj = HolmAdjust({0.01, 0.02, 0.03, 0.04, 0.05});
  const double want[] = {0.05, 0.08, 0.09, 0.09, 0.09};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(adj[i], want[i], 1e-15);
  // Input order is kept; capped at 1.
  const auto adj2 = HolmAdjust({0.5, 0.01, 0.4});
  // {0.5, 0.01, 0.4}, m = 3,
  // sorted: .01*3=.03, .4*2=.8, .5*1=.5 -> cummax .8 => p[0]=.8, p[1]=.03, p[2]=.8
  EXPECT_NEAR(adj2[0], 0.8, 1e-15);
  EXPECT_NEAR(adj2[1], 0.03, 1e-15);
  EXPECT_NEAR(adj2[2], 0.8, 1e-15);
  EXPECT_TRUE(HolmAdjust({}).empty());
}

TEST(WilcoxonTest, RDocumentationExample) {
  // ?wilcox.test: depression scale before (x) and after (y); V = 40,
  // two-sided exact p = 0.03906 (= 20/512).
  const std::vector<double> x = {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const std::vector<double> y = {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};
  const auto r = WilcoxonSignedRank(x, y);
  ASSERT_TRUE(r.valid);
  EXPECT_TRUE(r.exact);
  EXPECT_EQ(r.n_used, 9);
  EXPECT_DOUBLE_EQ(r.v, 40);
  EXPECT_NEAR(r.p, 20.0 / 512, 1e-15);
  // Swapping the samples mirrors V (45 - 40) and keeps p.
  const auto s = WilcoxonSignedRank(y, x);
  EXPECT_DOUBLE_EQ(s.v, 5);
  EXPECT_NEAR(s.p, 20.0 / 512, 1e-15);
}

TEST(WilcoxonTest, NormalApproximationWithTiesAndZeros) {
  // d = x - y = {1, 1, -2, 3, 3, 3, 4, 0}: the zero is dropped -> n = 7.
  // |d| ranks: 1,1 -> 1.5; 2 -> 3; 3,3,3 -> 5; 4 -> 7. V = 1.5+1.5+5+5+5+7 = 25.
  // mean 7*8/4 = 14; var = 7*8*15/24 - ((8-2) + (27-3))/48 = 35 - 0.625 = 34.375.
  // z = (25 - 14 - 0.5)/sqrt(34.375) = 1.7908860; p = 2*(1 - Phi(z)) = 0.0733116.
  const std::vector<double> x = {1, 1, -2, 3, 3, 3, 4, 5};
  const std::vector<double> y = {0, 0, 0, 0, 0, 0, 0, 5};
  const auto r = WilcoxonSignedRank(x, y);
  ASSERT_TRUE(r.valid);
  EXPECT_FALSE(r.exact);
  EXPECT_EQ(r.n_used, 7);
  EXPECT_DOUBLE_EQ(r.v, 25);
  EXPECT_NEAR(r.z, 1.7908860173871275, 1e-12);
  EXPECT_NEAR(r.p, 0.07331158795794018, 1e-12);
}

TEST(WilcoxonTest, ScoresThatDifferOnlyByRoundingAreTies) {
  // 2/3 - 1/3 and 1/3 - 0 are equal in exact arithmetic; they must tie.
  const auto r = WilcoxonSignedRank({2.0 / 3, 1.0 / 3, 1.0}, {1.0 / 3, 0.0, 0.0});
  EXPECT_FALSE(r.exact);  // ties -> normal approximation
  EXPECT_DOUBLE_EQ(r.v, 6);
}

TEST(WilcoxonTest, DegenerateInputs) {
  const auto same = WilcoxonSignedRank({1, 2, 3}, {1, 2, 3});
  EXPECT_TRUE(same.valid);
  EXPECT_EQ(same.n_used, 0);
  EXPECT_EQ(same.p, 1);
  EXPECT_FALSE(WilcoxonSignedRank({1, 2}, {1}).valid);
  EXPECT_FALSE(WilcoxonSignedRank({1, NAN}, {1, 2}).valid);
  // One pair: exact, V = 1 of max 1, p = 2 * 1/2 = 1.
  const auto one = WilcoxonSignedRank({2}, {1});
  EXPECT_TRUE(one.exact);
  EXPECT_EQ(one.p, 1);
  // Large n uses the normal approximation and stays finite.
  std::vector<double> a(200), b(200, 0.0);
  for (int i = 0; i < 200; ++i) a[i] = 1e6 * (i + 1);
  const auto big = WilcoxonSignedRank(a, b);
  EXPECT_FALSE(big.exact);
  EXPECT_GT(big.p, 0);
  EXPECT_LT(big.p, 1e-30);
}

TEST(FriedmanTest, RDocumentationRoundingTimes) {
  // ?friedman.test, Hollander & Wolfe (1973) p. 140: rounding first base,
  // methods "Round Out", "Narrow Angle", "Wide Angle", 22 players.
  // Friedman chi-squared = 11.143, df = 2, p-value = 0.003805.
  const std::vector<std::vector<double>> rt = {
      {5.40, 5.50, 5.55}, {5.85, 5.70, 5.75}, {5.20, 5.60, 5.50}, {5.55, 5.50, 5.40},
      {5.90, 5.85, 5.70}, {5.45, 5.55, 5.60}, {5.40, 5.40, 5.35}, {5.45, 5.50, 5.35},
      {5.25, 5.15, 5.00}, {5.85, 5.80, 5.70}, {5.25, 5.20, 5.10}, {5.65, 5.55, 5.45},
      {5.60, 5.35, 5.45}, {5.05, 5.00, 4.95}, {5.50, 5.50, 5.40}, {5.45, 5.55, 5.50},
      {5.55, 5.55, 5.35}, {5.45, 5.50, 5.55}, {5.50, 5.45, 5.25}, {5.65, 5.60, 5.40},
      {5.70, 5.65, 5.55}, {6.30, 6.30, 6.25}};
  const auto r = FriedmanTest(rt);
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.blocks, 22);
  EXPECT_EQ(r.treatments, 3);
  EXPECT_EQ(r.df, 2);
  EXPECT_NEAR(r.statistic, 11.143, 5e-4);
  EXPECT_NEAR(r.p, 0.003805, 5e-7);
}

TEST(FriedmanTest, ByHandNoTies) {
  // 3 blocks, all ranking treatments the same way: rank sums 3, 6, 9;
  // expected 6; SS = 18; stat = 12*18/(3*3*4) = 6; p = exp(-3) (df 2).
  const auto r = FriedmanTest({{1, 2, 3}, {10, 20, 30}, {0.1, 0.2, 0.3}});
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.statistic, 6, 1e-12);
  EXPECT_NEAR(r.p, std::exp(-3.0), 1e-12);
}

TEST(FriedmanTest, Degenerate) {
  EXPECT_FALSE(FriedmanTest({}).valid);
  EXPECT_FALSE(FriedmanTest({{1}, {2}}).valid);
  EXPECT_FALSE(FriedmanTest({{1, 2}, {1}}).valid);
  const auto ties = FriedmanTest({{1, 1, 1}, {2, 2, 2}});
  EXPECT_FALSE(ties.valid);
  EXPECT_FALSE(ties.reason.empty());
}

TEST(ShapiroWilkTest, ToothGrowthLength) {
  // R: shapiro.test(ToothGrowth$len) -> W = 0.96743, p-value = 0.1091.
  const std::vector<double> len = {
      4.2,  11.5, 7.3,  5.8,  6.4,  10,   11.2, 11.2, 5.2,  7,    16.5, 16.5, 15.2, 17.3, 22.5,
      17.3, 13.6, 14.5, 18.8, 15.5, 23.6, 18.5, 33.9, 25.5, 26.4, 32.5, 26.7, 21.5, 23.3, 29.5,
      15.2, 21.5, 17.6, 9.7,  14.5, 10,   8.2,  9.4,  16.5, 9.7,  19.7, 23.3, 23.6, 26.4, 20,
      25.2, 25.8, 21.2, 14.5, 27.3, 25.5, 26.4, 22.4, 24.5, 24.8, 30.9, 26.4, 27.3, 29.4, 23};
  const auto r = ShapiroWilk(len);
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.n, 60);
  EXPECT_NEAR(r.w, 0.96743, 5e-6);
  EXPECT_NEAR(r.p, 0.1091, 5e-5);
  // Invariant to shift, scale (1e6) and order.
  std::vector<double> scaled;
  for (auto it = len.rbegin(); it != len.rend(); ++it) scaled.push_back(1e6 * *it + 3e7);
  const auto s = ShapiroWilk(scaled);
  EXPECT_NEAR(s.w, r.w, 1e-12);
  EXPECT_NEAR(s.p, r.p, 1e-10);
}

TEST(ShapiroWilkTest, ShapiroWilk1965WeightsOfElevenMen) {
  // The worked example of Shapiro & Wilk (1965, Biometrika 52): weights in
  // pounds of 11 men, W = 0.79 (significant at the 1% level). R:
  // shapiro.test(c(148,154,158,160,161,162,166,170,182,195,236)) gives
  // W = 0.78881, p-value = 0.006704. Exercises the 4 <= n <= 11 branch of
  // Royston's p-value.
  const auto r = ShapiroWilk({148, 154, 158, 160, 161, 162, 166, 170, 182, 195, 236});
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.n, 11);
  EXPECT_NEAR(r.w, 0.78881, 5e-6);
  EXPECT_NEAR(r.p, 0.006704, 5e-7);
}

TEST(ShapiroWilkTest, ExactForThree) {
  // n = 3: a = (-sqrt(.5), 0, sqrt(.5)). x = {1, 2, 4}: (a.x)^2 = 4.5,
  // SS = 42/9 -> W = 0.9642857; p = (6/pi)(asin(sqrt W) - pi/3) = 0.6368868.
  const auto r = ShapiroWilk({4, 1, 2});
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.w, 0.9642857142857142, 1e-12);
  EXPECT_NEAR(r.p, 0.6368868450289692, 1e-10);
  // Equally spaced: W = 1, p = 1.
  const auto e = ShapiroWilk({1, 2, 3});
  EXPECT_NEAR(e.w, 1, 1e-12);
  EXPECT_NEAR(e.p, 1, 1e-6);
}

TEST(ShapiroWilkTest, SkewedSmallSampleIsRejectedAndBadInputHandled) {
  // A single huge outlier in n = 8 (the n <= 11 branch) is far from normal.
  const auto r = ShapiroWilk({1, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 100});
  ASSERT_TRUE(r.valid);
  EXPECT_LT(r.w, 0.6);
  EXPECT_LT(r.p, 0.001);
  EXPECT_GE(r.p, 0);
  EXPECT_FALSE(ShapiroWilk({1, 2}).valid);
  EXPECT_FALSE(ShapiroWilk({5, 5, 5, 5}).valid);
  EXPECT_FALSE(ShapiroWilk(std::vector<double>(5001, 1.0)).valid);
  EXPECT_FALSE(ShapiroWilk({1, 2, INFINITY}).valid);
}

}  // namespace
}  // namespace hapcine::study
