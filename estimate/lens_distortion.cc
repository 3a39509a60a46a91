#include "estimate/lens_distortion.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <unordered_map>

#include "core/statistics.h"
#include "estimate/geometry/reference_width.h"

namespace hapcine {
namespace {

// Frame pairs: at least this median motion (share of the width) and this
// many shared tracks; at most this many pairs (a few hundred tracks each is
// plenty for one parameter).
constexpr double kPairMotionShare = 0.03;
constexpr double kMaxPairMotionShare = 0.15;
constexpr int kMinPairTracks = 40;
constexpr int kMaxPairs = 8;
// RANSAC threshold, px at the reference width.
constexpr double kRansacPx = 1.5;
// GRIC constants (Torr): r = 4 (two 2-D views), lambda3 = 2.
constexpr double kGricR = 4;
// The corner of the picture must move by at least this many noise sigmas
// under the chosen k1: a coefficient whose effect is under the noise is
// not a finding, whatever the sum of many small gains says.
constexpr double kMinCornerEffectSigmas = 2;
// At least this share of the frame pairs a homography explains must fit
// better with k1, and at least 3 such pairs.
constexpr double kConsistentShare = 0.75;
constexpr int kMinPairs = 3;

struct Pair {
  std::vector<cv::Point2d> a, b;  // normalised by the half-diagonal, centred
  std::vector<uchar> h_inliers, f_inliers;
  // GRIC of the fundamental matrix on the tracks as they are (k1 = 0).
  double f_cost = 0;
};

double HalfDiagonal(int width, int height) { return 0.5 * std::hypot(width, height); }

// Shared tracks of two frames, in normalised coordinates.
Pair MakePair(const FrameTracks& first, const FrameTracks& second, int width, int height) {
  std::unordered_map<long, Eigen::Vector2d> at_first;
  for (const TrackPoint& p : first.points) at_first.emplace(p.track_id, p.px);
  const Eigen::Vector2d c((width - 1) / 2.0, (height - 1) / 2.0);
  const double s = HalfDiagonal(width, height);
  Pair pair;
  for (const TrackPoint& p : second.points) {
    const auto it = at_first.find(p.track_id);
    if (it == at_first.end()) continue;
    const Eigen::Vector2d qa = (it->second - c) / s, qb = (p.px - c) / s;
    pair.a.emplace_back(qa.x(), qa.y());
    pair.b.emplace_back(qb.x(), qb.y());
  }
  return pair;
}

double MedianMotion(const Pair& pair) {
  std::vector<double> d;
  for (size_t i = 0; i < pair.a.size(); ++i) d.push_back(cv::norm(pair.a[i] - pair.b[i]));
  return d.empty() ? 0 : Median(d);
}

// Pairs of frames far enough apart, consecutive (each starts where the last
// ended), within the first shot of `frames`. Each pair spans as much motion
// as it can, up to `max_motion_share` of the width.
std::vector<Pair> SelectPairs(const std::vector<FrameTracks>& frames, int width, int height,
                              double max_motion_share) {
  std::vector<Pair> pairs;
  const double min_motion = kPairMotionShare * width / HalfDiagonal(width, height);
  const double max_motion = max_motion_share * width / HalfDiagonal(width, height);
  size_t from = 0;
  while (from + 1 < frames.size() && static_cast<int>(pairs.size()) < kMaxPairs) {
    Pair longest;
    size_t end = from;
    for (size_t j = from + 1; j < frames.size() && frames[j].shot == frames[from].shot; ++j) {
      Pair p = MakePair(frames[from], frames[j], width, height);
      if (static_cast<int>(p.a.size()) < kMinPairTracks) break;  // the tracks thinned out
      longest = std::move(p);
      end = j;
      if (MedianMotion(longest) >= max_motion) break;
    }
    if (end == from) {  // nothing shared with the next frame: start again there
      if (frames[from + 1].shot != frames[from].shot) break;
      ++from;
      continue;
    }
    if (MedianMotion(longest) >= min_motion) pairs.push_back(std::move(longest));
    else if (end + 1 >= frames.size() || frames[end + 1].shot != frames[from].shot) break;
    from = end;
  }
  return pairs;
}

std::vector<cv::Point2d> Undistorted(const std::vector<cv::Point2d>& q, double k1) {
  std::vector<cv::Point2d> out(q.size());
  for (size_t i = 0; i < q.size(); ++i) out[i] = q[i] * (1 + k1 * q[i].dot(q[i]));
  return out;
}

std::vector<cv::Point2d> Subset(const std::vector<cv::Point2d>& v, const std::vector<uchar>& keep) {
  std::vector<cv::Point2d> out;
  for (size_t i = 0; i < v.size(); ++i)
    if (keep[i]) out.push_back(v[i]);
  return out;
}

// Squared residuals of every correspondence: half the squared transfer
// error under H, the squared Sampson distance under F (model_selection.h's
// conventions). Empty when the fit fails.
std::vector<double> HomographyResiduals(const std::vector<cv::Point2d>& a,
                                        const std::vector<cv::Point2d>& b,
                                        const std::vector<uchar>& inliers) {
  const std::vector<cv::Point2d> ia = Subset(a, inliers), ib = Subset(b, inliers);
  if (ia.size() < 8) return {};
  const cv::Mat h = cv::findHomography(ia, ib, 0);
  if (h.empty()) return {};
  const cv::Matx33d H(h);
  std::vector<double> e(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const cv::Vec3d x = H * cv::Vec3d(a[i].x, a[i].y, 1);
    const cv::Point2d t(x[0] / x[2], x[1] / x[2]);
    e[i] = 0.5 * (t - b[i]).dot(t - b[i]);
  }
  return e;
}

std::vector<double> FundamentalResiduals(const std::vector<cv::Point2d>& a,
                                         const std::vector<cv::Point2d>& b,
                                         const std::vector<uchar>& inliers) {
  const std::vector<cv::Point2d> ia = Subset(a, inliers), ib = Subset(b, inliers);
  if (ia.size() < 12) return {};
  const cv::Mat f = cv::findFundamentalMat(ia, ib, cv::FM_8POINT);
  if (f.rows != 3 || f.cols != 3) return {};
  const cv::Matx33d F(f);
  std::vector<double> e(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const cv::Vec3d x1(a[i].x, a[i].y, 1), x2(b[i].x, b[i].y, 1);
    const cv::Vec3d fx1 = F * x1, ftx2 = F.t() * x2;
    const double num = x2.dot(fx1);
    const double den = fx1[0] * fx1[0] + fx1[1] * fx1[1] + ftx2[0] * ftx2[0] + ftx2[1] * ftx2[1];
    e[i] = den > 0 ? num * num / den : 0;
  }
  return e;
}

double Gric(const std::vector<double>& e2, double sigma, int d) {
  if (e2.empty()) return std::numeric_limits<double>::infinity();
  const double cap = 2 * (kGricR - d), n = static_cast<double>(e2.size());
  double g = std::log(kGricR) * d * n;
  for (double e : e2) g += std::min(e / (sigma * sigma), cap);
  return g;
}

// The pair's cost under k1: the better by GRIC of a homography on the
// tracks undistorted by k1 and the fundamental matrix on the tracks as they
// are. Only the homography is refitted: radial distortion is not projective,
// so H cannot absorb it and k1 is measured where H explains the pair (a pan,
// a roll, a zoom, a plane). F's 7 degrees of freedom absorb a distortion
// (on a rotation, on a near-planar scene, along forward motion's radial
// epipolar lines), so F's cost under k1 measures nothing, and a distorted
// pan would choose F at k1 = 0: the choice is made again at every k1.
double PairCost(const Pair& p, double k1, double sigma) {
  const std::vector<cv::Point2d> a = Undistorted(p.a, k1), b = Undistorted(p.b, k1);
  return std::min(p.f_cost, Gric(HomographyResiduals(a, b, p.h_inliers), sigma, 2));
}

void CostFundamentals(std::vector<Pair>* pairs, double sigma) {
  for (Pair& p : *pairs) p.f_cost = Gric(FundamentalResiduals(p.a, p.b, p.f_inliers), sigma, 3);
}

// Of the pairs that measure k1, how many it improves, and how many there
// are: a lens is the same in every pair, noise is not. A pair measures k1
// when a homography explains it (better than F) at k1 or at 0.
std::pair<int, int> PairsImproved(const std::vector<Pair>& pairs, double k1, double sigma) {
  int improved = 0, measuring = 0;
  for (const Pair& p : pairs) {
    const double at_k1 = PairCost(p, k1, sigma), at_zero = PairCost(p, 0, sigma);
    if (!(at_k1 < p.f_cost || at_zero < p.f_cost)) continue;
    ++measuring;
    improved += at_k1 < at_zero;
  }
  return {improved, measuring};
}

double TotalCost(const std::vector<Pair>& pairs, double k1, double sigma) {
  double total = 0;
  for (const Pair& p : pairs) total += PairCost(p, k1, sigma);
  return total;
}

// RANSAC inliers at k1 = 0, and the noise sigma from the better model's
// inlier residuals (normalised units).
double PrepareAtZero(std::vector<Pair>* pairs, double ransac, double floor) {
  std::vector<double> residuals;
  for (Pair& p : *pairs) {
    cv::findHomography(p.a, p.b, cv::RANSAC, ransac, p.h_inliers);
    cv::findFundamentalMat(p.a, p.b, cv::FM_RANSAC, ransac, 0.999, p.f_inliers);
    if (p.h_inliers.size() != p.a.size()) p.h_inliers.assign(p.a.size(), 1);
    if (p.f_inliers.size() != p.a.size()) p.f_inliers.assign(p.a.size(), 1);
    std::vector<double> e = FundamentalResiduals(p.a, p.b, p.f_inliers);
    for (size_t i = 0; i < e.size(); ++i)
      if (p.f_inliers[i]) residuals.push_back(std::sqrt(e[i]));
  }
  if (residuals.empty()) return floor;
  return std::max(floor, Median(residuals) / 0.6745);
}

}  // namespace

Eigen::Vector2d UndistortRadial(const Eigen::Vector2d& px, double k1, int width, int height) {
  if (k1 == 0) return px;
  const Eigen::Vector2d c((width - 1) / 2.0, (height - 1) / 2.0);
  const double s = HalfDiagonal(width, height);
  const Eigen::Vector2d q = (px - c) / s;
  return c + (px - c) * (1 + k1 * q.squaredNorm());
}

void UndistortTracks(double k1, int width, int height, FrameTracks* tracks) {
  if (k1 == 0) return;
  for (TrackPoint& p : tracks->points) p.px = UndistortRadial(p.px, k1, width, height);
}

RadialDistortionEstimate EstimateRadialDistortion(const std::vector<FrameTracks>& frames,
                                                  int width, int height, double max_abs_k1) {
  RadialDistortionEstimate out;
  if (width <= 0 || height <= 0) return out;
  // Long pairs: a distortion's signature grows with the motion (the change
  // of r^2 under it), the noise does not. Footage too slow for 3 of them
  // gets 3 % pairs instead: weaker, but a strong lens still shows.
  std::vector<Pair> pairs = SelectPairs(frames, width, height, kMaxPairMotionShare);
  if (static_cast<int>(pairs.size()) < kMinPairs) pairs = SelectPairs(frames, width, height, kPairMotionShare);
  out.pairs = static_cast<int>(pairs.size());
  if (out.pairs < kMinPairs) return out;
  const double px = 1 / HalfDiagonal(width, height) * width / kReferenceWidthPx;  // 1 ref px
  const double sigma = PrepareAtZero(&pairs, kRansacPx * px, kLensNoiseFloorPx * px);
  CostFundamentals(&pairs, sigma);
  for (const Pair& p : pairs) out.correspondences += static_cast<int>(p.a.size());
  // Grid, then golden-section search around the best grid point.
  const double step = 0.01;
  double best = 0, best_cost = TotalCost(pairs, 0, sigma);
  const double cost_at_zero = best_cost;
  for (double k = -max_abs_k1; k <= max_abs_k1 + 1e-12; k += step) {
    const double c = TotalCost(pairs, k, sigma);
    if (c < best_cost) best_cost = c, best = k;
  }
  double lo = best - step, hi = best + step;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 20; ++it) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (TotalCost(pairs, m1, sigma) < TotalCost(pairs, m2, sigma)) hi = m2; else lo = m1;
  }
  const double refined = 0.5 * (lo + hi);
  const double refined_cost = TotalCost(pairs, refined, sigma);
  if (refined_cost < best_cost) best = refined, best_cost = refined_cost;
  out.best_k1 = best;
  out.gric_gain = cost_at_zero - best_cost;
  out.penalty = std::log(kGricR * out.correspondences);
  // The corner (r = 1) moves by |k1| half-diagonals.
  const bool visible = std::abs(best) >= std::max(kMinCornerEffectSigmas * sigma, kMinLensK1);
  // At the end of the search range: no lens, a model the data break.
  const bool inside = std::abs(best) < max_abs_k1 - step;
  const auto [improved, measuring] = PairsImproved(pairs, best, sigma);
  const bool consistent = measuring >= kMinPairs && improved >= kConsistentShare * measuring;
  if (out.gric_gain > out.penalty && visible && inside && consistent) out.k1 = best;
  return out;
}

}  // namespace hapcine
