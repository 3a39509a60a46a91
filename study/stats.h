#pragma once
// Statistics for the pairwise user study (paper, section 5.3): the tests the
// paper used, implemented to match R's stats package so that numbers can be
// checked against R's documented examples.
//
//   ShapiroWilk      normality of each condition's scores (Royston 1995, AS R94)
//   FriedmanTest     non-parametric repeated-measures ANOVA across conditions
//   WilcoxonSignedRank  paired comparison of two conditions
//   HolmAdjust       Holm–Bonferroni step-down adjustment of a p-value family
//
// Special functions they need (normal CDF and quantile, regularised incomplete
// gamma for the chi-square tail) are here too. Nothing returns NaN: a test that
// is undefined for its input (constant data, too few values) says so through
// its `valid` flag and a reason.

#include <string>
#include <vector>

namespace hapcine::study {

// Standard normal CDF Phi(x) and its upper tail 1 - Phi(x), computed with
// erfc so the tails keep full relative precision.
double NormalCdf(double x);
double NormalSf(double x);
// Standard normal quantile Phi^-1(p) for p in (0,1): Acklam's rational
// approximation refined by one Halley step (|error| ~1e-15). p <= 0 -> -inf,
// p >= 1 -> +inf.
double NormalQuantile(double p);

// Regularised lower/upper incomplete gamma P(a,x), Q(a,x) = 1 - P(a,x), a > 0,
// x >= 0 (series for x < a+1, Lentz continued fraction otherwise).
double GammaP(double a, double x);
double GammaQ(double a, double x);
// Upper tail of the chi-square distribution: P(X >= x) with `df` degrees of
// freedom (df > 0).
double ChiSquareSf(double x, double df);

struct ShapiroWilkResult {
  bool valid = false;  // false: n outside 3..5000 or constant data
  std::string reason;  // why not valid
  int n = 0;
  double w = 1;  // the W statistic, in (0,1]
  double p = 1;  // p-value (exact for n = 3, Royston's approximation otherwise)
};
// Shapiro–Wilk W test, Royston (1995) algorithm AS R94 as in R's shapiro.test:
// coefficients from Royston's polynomial approximation to the expected normal
// order statistics, W as the squared correlation between sorted data and
// coefficients, p from Royston's normalising transformation (separate fits
// for 4 <= n <= 11 and n >= 12; exact for n = 3). Input need not be sorted.
ShapiroWilkResult ShapiroWilk(std::vector<double> x);

struct FriedmanResult {
  bool valid = false;
  std::string reason;
  int blocks = 0;        // n: rows (participants)
  int treatments = 0;    // k: columns (conditions)
  double statistic = 0;  // Friedman chi-squared, tie-corrected
  double df = 0;         // k - 1
  double p = 1;          // chi-square(df) upper tail
};
// Friedman rank-sum test on a complete block design: data[block][treatment].
// Within each block the values are ranked (ties get the average rank); the
// statistic is R's:
//   12 * sum_j (R_j - n(k+1)/2)^2 / (n k (k+1) - sum_ties(t^3 - t)/(k-1)).
// Not valid if k < 2, n < 1, rows of unequal length, or every block is all
// ties (the statistic is 0/0).
FriedmanResult FriedmanTest(const std::vector<std::vector<double>>& data);

struct WilcoxonResult {
  bool valid = false;
  std::string reason;
  int n_pairs = 0;     // pairs given
  int n_used = 0;      // pairs with a non-zero difference
  double v = 0;        // V: sum of the ranks of the positive differences (x - y)
  bool exact = false;  // exact null distribution used
  double z = 0;        // normal-approximation z (continuity- and tie-corrected); 0 if exact
  double p = 1;        // two-sided p-value
};
// Wilcoxon signed-rank test of paired samples x, y (two-sided), as R's
// wilcox.test(x, y, paired = TRUE):
//  * zero differences are dropped (Wilcoxon's method), reducing n;
//  * |d| ranked with average ranks for ties;
//  * exact p from the null distribution of V when n_used < 50 and there are
//    neither ties nor zeros; otherwise the normal approximation with the tie
//    correction of the variance and a continuity correction of 0.5.
// All differences zero -> valid with p = 1 and n_used = 0 (the samples are
// identical: no evidence of a difference); R would return NaN here.
WilcoxonResult WilcoxonSignedRank(const std::vector<double>& x, const std::vector<double>& y);

// Holm–Bonferroni adjusted p-values, in the input order (R's p.adjust "holm"):
// sort ascending, p'_(i) = max_{j<=i} min(1, (m - j + 1) p_(j)).
std::vector<double> HolmAdjust(const std::vector<double>& p);

// Average ranks (1-based) of `x`, ties sharing the mean of their ranks.
std::vector<double> AverageRanks(const std::vector<double>& x);

}  // namespace hapcine::study
