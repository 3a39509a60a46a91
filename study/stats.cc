#include "study/stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>

namespace hapcine::study {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rounds to 12 significant digits so that differences of scores that are
// equal in exact arithmetic (2/3 - 1/3 and 1/3 - 0) rank as ties, as they
// would by hand. Data with fewer significant digits (all of R's examples) are
// unchanged.
double Snap(double v) {
  if (v == 0 || !std::isfinite(v)) return v;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return std::strtod(buf, nullptr);
}

// c[0] + c[1] x + ... + c[n-1] x^(n-1)  (R's swilk.c `poly`).
double Poly(const double* c, int n, double x) {
  double r = 0;
  for (int i = n - 1; i >= 0; --i) r = r * x + c[i];
  return r;
}

}  // namespace

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double NormalSf(double x) { return 0.5 * std::erfc(x / std::sqrt(2.0)); }

double NormalQuantile(double p) {
  if (!(p > 0)) return -kInf;
  if (!(p < 1)) return kInf;
  // Acklam (2003) rational approximation, relative error < 1.15e-9 ...
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double p_low = 0.02425;
  double x;
  if (p < p_low) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - p_low) {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log1p(-p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  // ... then one Halley step on Phi(x) - p brings it to machine precision.
  // Use the tail on the side where it is small so the residual keeps its
  // relative precision.
  const double e = (p < 0.5) ? NormalCdf(x) - p : (1 - p) - NormalSf(x);
  const double u = e * std::sqrt(2 * M_PI) * std::exp(x * x / 2);
  x = x - u / (1 + x * u / 2);
  return x;
}

double GammaP(double a, double x) {
  if (x <= 0) return 0;
  if (x < a + 1) {
    // Series: P = e^-x x^a / Gamma(a+1) * sum x^n / ((a+1)...(a+n)).
    double ap = a, sum = 1 / a, del = sum;
    for (int n = 0; n < 10000; ++n) {
      ap += 1;
      del *= x / ap;
      sum += del;
      if (std::fabs(del) < std::fabs(sum) * 1e-16) break;
    }
    return std::min(1.0, sum * std::exp(-x + a * std::log(x) - std::lgamma(a)));
  }
  return 1 - GammaQ(a, x);
}

double GammaQ(double a, double x) {
  if (x <= 0) return 1;
  if (x < a + 1) return 1 - GammaP(a, x);
  // Continued fraction (modified Lentz), Numerical Recipes gcf.
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1) < 1e-16) break;
  }
  return std::max(0.0, std::exp(-x + a * std::log(x) - std::lgamma(a)) * h);
}

double ChiSquareSf(double x, double df) {
  if (!(x > 0)) return 1;
  return GammaQ(df / 2, x / 2);
}

std::vector<double> AverageRanks(const std::vector<double>& x) {
  const size_t n = x.size();
  std::vector<size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](size_t i, size_t j) { return x[i] < x[j]; });
  std::vector<double> rank(n);
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j + 1 < n && x[idx[j + 1]] == x[idx[i]]) ++j;
    const double r = (static_cast<double>(i + 1) + static_cast<double>(j + 1)) / 2;
    for (size_t k = i; k <= j; ++k) rank[idx[k]] = r;
    i = j + 1;
  }
  return rank;
}

namespace {

// Why x cannot be tested (empty: it can). Sorts x.
std::string ShapiroWilkRefusal(std::vector<double>* x) {
  const int n = static_cast<int>(x->size());
  if (n < 3 || n > 5000) return "Shapiro-Wilk needs 3 to 5000 values, got " + std::to_string(n);
  for (double v : *x) {
    if (!std::isfinite(v)) return "non-finite value";
  }
  std::sort(x->begin(), x->end());
  const double range = (*x)[n - 1] - (*x)[0];
  if (!(range > 1e-19 * std::max(1.0, std::fabs((*x)[0])))) return "all values are identical";
  return "";
}

// Coefficients a[1..n/2] (1-based) for the upper half of n sorted values;
// the lower half is antisymmetric (AS R94).
std::vector<double> ShapiroWilkCoefficients(int n) {
  const int nn2 = n / 2;
  std::vector<double> a(nn2 + 1, 0.0);  // 1-based
  const double an = n;
  if (n == 3) {
    a[1] = std::sqrt(0.5);
    return a;
  }
  static const double c1[6] = {0., .221157, -.147981, -2.07119, 4.434685, -2.706056};
  static const double c2[6] = {0., .042981, -.293762, -1.752461, 5.682633, -3.582633};
  const double an25 = an + .25;
  double summ2 = 0;
  for (int i = 1; i <= nn2; ++i) {
    a[i] = NormalQuantile((i - .375) / an25);  // m_i, negative for the lower half
    summ2 += a[i] * a[i];
  }
  summ2 *= 2;
  const double ssumm2 = std::sqrt(summ2);
  const double rsn = 1 / std::sqrt(an);
  const double a1 = Poly(c1, 6, rsn) - a[1] / ssumm2;
  int i1;
  double fac;
  if (n > 5) {
    i1 = 3;
    const double a2 = -a[2] / ssumm2 + Poly(c2, 6, rsn);
    fac = std::sqrt((summ2 - 2 * a[1] * a[1] - 2 * a[2] * a[2]) / (1 - 2 * a1 * a1 - 2 * a2 * a2));
    a[2] = a2;
  } else {
    i1 = 2;
    fac = std::sqrt((summ2 - 2 * a[1] * a[1]) / (1 - 2 * a1 * a1));
  }
  a[1] = a1;
  for (int i = i1; i <= nn2; ++i) a[i] /= -fac;
  return a;
}

// 1 - W, W the squared correlation between the sorted data and the full
// (antisymmetric) coefficient vector. 1 - W is computed directly (as AS R94
// does) to avoid cancellation when W is very near 1.
double OneMinusW(const std::vector<double>& sorted, const std::vector<double>& a) {
  const int n = static_cast<int>(sorted.size());
  const int nn2 = n / 2;
  const double range = sorted[n - 1] - sorted[0];
  std::vector<double> coef(n, 0.0);
  for (int i = 0; i < nn2; ++i) {
    coef[i] = -a[i + 1];
    coef[n - 1 - i] = a[i + 1];
  }
  double sa = 0, sx = 0;
  for (int i = 0; i < n; ++i) {
    sa += coef[i];
    sx += sorted[i] / range;
  }
  sa /= n;
  sx /= n;
  double ssa = 0, ssx = 0, sax = 0;
  for (int i = 0; i < n; ++i) {
    const double asa = coef[i] - sa;
    const double xsx = sorted[i] / range - sx;
    ssa += asa * asa;
    ssx += xsx * xsx;
    sax += asa * xsx;
  }
  const double ssassx = std::sqrt(ssa * ssx);
  return (ssassx - sax) * (ssassx + sax) / (ssa * ssx);
}

// The p-value of W = 1 - w1 for n values (AS R94: exact for n = 3, else
// Royston's normalising transformations).
double ShapiroWilkP(int n, double w1) {
  const double an = n;
  if (n == 3) {  // exact
    const double pi6 = 6 / M_PI, stqr = M_PI / 3;
    return std::clamp(pi6 * (std::asin(std::sqrt(1 - w1)) - stqr), 0.0, 1.0);
  }
  if (!(w1 > 0)) return 1;  // W == 1 to machine precision: perfectly "normal" order statistics
  double y = std::log(w1);
  const double xx = std::log(an);
  double m, s;
  if (n <= 11) {
    static const double g[2] = {-2.273, .459};
    static const double c3[4] = {.544, -.39978, .025054, -6.714e-4};
    static const double c4[4] = {1.3822, -.77857, .062767, -.0020322};
    const double gamma = Poly(g, 2, an);
    if (y >= gamma) return 1e-99;  // as AS R94: far in the tail
    y = -std::log(gamma - y);
    m = Poly(c3, 4, an);
    s = std::exp(Poly(c4, 4, an));
  } else {
    static const double c5[4] = {-1.5861, -.31082, -.083751, .0038915};
    static const double c6[3] = {-.4803, -.082676, .0030302};
    m = Poly(c5, 4, xx);
    s = std::exp(Poly(c6, 3, xx));
  }
  return std::clamp(NormalSf((y - m) / s), 0.0, 1.0);
}

// Sum over the groups of equal values of t^3 - t (t: the group's size), the
// tie correction of rank tests' variances.
double TieCorrection(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const int n = static_cast<int>(values.size());
  double sum = 0;
  for (int i = 0; i < n;) {
    int j = i;
    while (j + 1 < n && values[j + 1] == values[i]) ++j;
    const double t = j - i + 1;
    sum += t * t * t - t;
    i = j + 1;
  }
  return sum;
}

// Two-sided p of the signed-rank statistic v over n untied, non-zero
// differences: counts the subsets of {1..n} by rank sum (v is then an integer).
double ExactSignedRankP(int n, double v) {
  const int max_sum = n * (n + 1) / 2;
  std::vector<double> count(max_sum + 1, 0.0);
  count[0] = 1;
  for (int i = 1; i <= n; ++i)
    for (int s = max_sum; s >= i; --s) count[s] += count[s - i];
  const int vi = static_cast<int>(std::lround(v));
  double lower = 0, upper = 0;  // P(V <= v), P(V >= v)
  for (int s = 0; s <= max_sum; ++s) {
    if (s <= vi) lower += count[s];
    if (s >= vi) upper += count[s];
  }
  return std::min(1.0, 2 * std::min(lower, upper) / std::ldexp(1.0, n));
}

}  // namespace

ShapiroWilkResult ShapiroWilk(std::vector<double> x) {
  ShapiroWilkResult res;
  res.n = static_cast<int>(x.size());
  res.reason = ShapiroWilkRefusal(&x);
  if (!res.reason.empty()) return res;
  const double w1 = OneMinusW(x, ShapiroWilkCoefficients(res.n));
  res.w = 1 - w1;
  res.valid = true;
  res.p = ShapiroWilkP(res.n, w1);
  return res;
}

FriedmanResult FriedmanTest(const std::vector<std::vector<double>>& data) {
  FriedmanResult res;
  const int n = static_cast<int>(data.size());
  const int k = n > 0 ? static_cast<int>(data[0].size()) : 0;
  res.blocks = n;
  res.treatments = k;
  if (n < 1 || k < 2) {
    res.reason = "Friedman test needs at least 1 block and 2 treatments";
    return res;
  }
  std::vector<double> rank_sum(k, 0.0);
  double tie_sum = 0;  // sum over blocks and tie groups of t^3 - t
  for (const auto& row : data) {
    if (static_cast<int>(row.size()) != k) {
      res.reason = "blocks of unequal length";
      return res;
    }
    std::vector<double> snapped(k);
    for (int j = 0; j < k; ++j) {
      if (!std::isfinite(row[j])) {
        res.reason = "non-finite value";
        return res;
      }
      snapped[j] = Snap(row[j]);
    }
    const auto r = AverageRanks(snapped);
    for (int j = 0; j < k; ++j) rank_sum[j] += r[j];
    tie_sum += TieCorrection(snapped);
  }
  double ss = 0;
  const double expected = n * (k + 1) / 2.0;
  for (double r : rank_sum) ss += (r - expected) * (r - expected);
  const double denom = static_cast<double>(n) * k * (k + 1) - tie_sum / (k - 1);
  if (!(denom > 1e-12)) {
    res.reason = "every block is all ties";
    return res;
  }
  res.statistic = 12 * ss / denom;
  res.df = k - 1;
  res.p = ChiSquareSf(res.statistic, res.df);
  res.valid = true;
  return res;
}

WilcoxonResult WilcoxonSignedRank(const std::vector<double>& x, const std::vector<double>& y) {
  WilcoxonResult res;
  if (x.size() != y.size()) {
    res.reason = "samples of unequal length";
    return res;
  }
  res.n_pairs = static_cast<int>(x.size());
  std::vector<double> d;
  bool zeroes = false;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      res.reason = "non-finite value";
      return res;
    }
    const double di = Snap(x[i] - y[i]);
    if (di == 0) {
      zeroes = true;
    } else {
      d.push_back(di);
    }
  }
  const int n = static_cast<int>(d.size());
  res.n_used = n;
  res.valid = true;
  if (n == 0) {  // identical samples
    res.p = 1;
    return res;
  }
  std::vector<double> absd(n);
  for (int i = 0; i < n; ++i) absd[i] = std::fabs(d[i]);
  const auto r = AverageRanks(absd);
  double v = 0;
  for (int i = 0; i < n; ++i)
    if (d[i] > 0) v += r[i];
  res.v = v;
  const double tie_sum = TieCorrection(absd);  // 0 exactly when no two |d| tie
  if (n < 50 && tie_sum == 0 && !zeroes) {
    res.exact = true;
    res.p = ExactSignedRankP(n, v);
    return res;
  }
  const double mean = n * (n + 1) / 4.0;
  const double var = n * (n + 1.0) * (2 * n + 1) / 24 - tie_sum / 48;
  if (!(var > 0)) {
    res.p = 1;
    return res;
  }
  double z = v - mean;
  const double correction = (z > 0) ? 0.5 : (z < 0 ? -0.5 : 0.0);
  z = (z - correction) / std::sqrt(var);
  res.z = z;
  res.p = std::min(1.0, 2 * std::min(NormalCdf(z), NormalSf(z)));
  return res;
}

std::vector<double> HolmAdjust(const std::vector<double>& p) {
  const size_t m = p.size();
  std::vector<size_t> idx(m);
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](size_t i, size_t j) { return p[i] < p[j]; });
  std::vector<double> out(m);
  double running = 0;
  for (size_t r = 0; r < m; ++r) {
    const double adj = std::min(1.0, static_cast<double>(m - r) * p[idx[r]]);
    running = std::max(running, adj);
    out[idx[r]] = running;
  }
  return out;
}

}  // namespace hapcine::study
