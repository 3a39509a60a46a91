#include "estimate/window/window_freedoms.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"

namespace hapcine {
namespace {

// The capped chi2 of two fits of the same observations, with one sigma
// measured from the first, the more general one (the median of |e| of a 2-D
// Gaussian residual is sigma sqrt(2 ln 2) = 1.1774 sigma; at least the floor).
struct Chi2Pair {
  double sigma = 0, general = 0, simpler = 0;
};

// sigma from residual magnitudes: their median / 1.1774, at least the floor.
double SigmaOf(const std::vector<double>& errors, double noise_floor) {
  return std::max(Median(errors, 0.0) / 1.1774, noise_floor);
}

// sum_i min(e_i^2 / (sigma^2 + blur_i^2), 9); a non-finite error counts 9.
// `blur_sigma`: per observation (BlurSigmas), or empty.
double CappedChi2(const std::vector<double>& e, double sigma, const std::vector<double>& blur_sigma = {}) {
  double sum = 0;
  for (size_t i = 0; i < e.size(); ++i) {
    const double b = i < blur_sigma.size() ? blur_sigma[i] : 0.0;
    const double var = sigma * sigma + b * b;
    sum += std::isfinite(e[i]) ? std::min(e[i] * e[i] / var, 9.0) : 9.0;
  }
  return sum;
}

Chi2Pair CappedChi2Pair(const std::vector<double>& e_general, const std::vector<double>& e_simpler,
                        double noise_floor, const std::vector<double>& blur_sigma) {
  Chi2Pair c;
  c.sigma = SigmaOf(e_general, noise_floor);
  c.general = CappedChi2(e_general, c.sigma, blur_sigma);
  c.simpler = CappedChi2(e_simpler, c.sigma, blur_sigma);
  return c;
}

double BicPenalty(double parameters, size_t observations) {
  return parameters * std::log(std::max(2.0 * static_cast<double>(observations), 2.0));
}

}  // namespace

std::vector<double> BlurSigmas(const std::vector<BaObservation>& observations,
                               const std::vector<int>& frame_of_camera, double per_speed) {
  std::vector<double> sigma(observations.size(), 0.0);
  if (!(per_speed > 0)) return sigma;
  // The point's observation at the nearest earlier and later cameras.
  std::vector<std::vector<std::pair<int, int>>> by_point;  // (camera, observation)
  for (size_t i = 0; i < observations.size(); ++i) {
    const BaObservation& o = observations[i];
    if (o.point < 0) continue;
    if (static_cast<size_t>(o.point) >= by_point.size()) by_point.resize(o.point + 1);
    by_point[o.point].emplace_back(o.camera, static_cast<int>(i));
  }
  const int cameras = static_cast<int>(frame_of_camera.size());
  for (auto& seen : by_point) {
    std::sort(seen.begin(), seen.end());
    for (size_t j = 0; j < seen.size(); ++j) {
      double speed = 0;
      for (size_t k : {j - 1, j + 1}) {  // j - 1 wraps to a huge index at j = 0
        if (k >= seen.size()) continue;
        const int a = seen[j].first, b = seen[k].first;
        if (a < 0 || b < 0 || a >= cameras || b >= cameras) continue;
        const int frames = std::abs(frame_of_camera[a] - frame_of_camera[b]);
        if (frames < 1) continue;
        const Eigen::Vector2d d = observations[seen[j].second].u - observations[seen[k].second].u;
        speed = std::max(speed, d.norm() / frames);
      }
      sigma[seen[j].second] = per_speed * speed;
    }
  }
  return sigma;
}

FreedomEvidence CompareFreedoms(const std::vector<BaCamera>& with_cams, const std::vector<BaPoint>& with_points,
                                const std::vector<BaCamera>& without_cams,
                                const std::vector<BaPoint>& without_points,
                                const std::vector<BaObservation>& observations,
                                const std::vector<char>& drop_translation, const std::vector<char>& drop_zoom,
                                double noise_floor, const std::vector<double>& blur_sigma) {
  FreedomEvidence ev;
  const Chi2Pair c = CappedChi2Pair(ObservationErrors(with_cams, with_points, observations, true),
                                    ObservationErrors(without_cams, without_points, observations, false),
                                    noise_floor, blur_sigma);
  ev.sigma = c.sigma;
  ev.chi2_with = c.general;
  ev.chi2_without = c.simpler;

  const int n = static_cast<int>(with_cams.size());
  auto at = [](const std::vector<char>& v, int i) { return i < static_cast<int>(v.size()) && v[i]; };
  // dropped_before[i]: intervals that lose their translation, ending at cameras < i.
  std::vector<int> dropped_before(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    ev.translation_dropped += at(drop_translation, i);
    ev.zoom_dropped += at(drop_zoom, i);
    if (at(drop_zoom, i) && i > 0) ev.zoom_change += std::abs(with_cams[i].log_focal - with_cams[i - 1].log_focal);
    dropped_before[i + 1] = dropped_before[i] + at(drop_translation, i);
  }
  // Which points' depths the dropped translation observes: those seen on
  // both sides of such an interval (cameras first..last span the intervals
  // ending at first+1..last).
  std::vector<int> first(with_points.size(), n), last(with_points.size(), -1);
  for (const BaObservation& o : observations) {
    first[o.point] = std::min(first[o.point], o.camera);
    last[o.point] = std::max(last[o.point], o.camera);
  }
  for (size_t k = 0; k < with_points.size(); ++k)
    if (last[k] > first[k] && dropped_before[last[k] + 1] > dropped_before[first[k] + 1]) ++ev.informed_points;
  ev.penalty = BicPenalty(3.0 * ev.translation_dropped + ev.zoom_dropped + ev.informed_points, observations.size());
  return ev;
}

PromotionEvidence ComparePromotion(const std::vector<BaCamera>& promoted_cams,
                                   const std::vector<BaPoint>& promoted_points,
                                   const std::vector<BaCamera>& current_cams,
                                   const std::vector<BaPoint>& current_points,
                                   const std::vector<BaObservation>& observations, int promoted,
                                   double noise_floor, const std::vector<double>& blur_sigma) {
  PromotionEvidence ev;
  const Chi2Pair c = CappedChi2Pair(ObservationErrors(promoted_cams, promoted_points, observations, true),
                                    ObservationErrors(current_cams, current_points, observations, true),
                                    noise_floor, blur_sigma);
  ev.sigma = c.sigma;
  ev.chi2_promoted = c.general;
  ev.chi2_current = c.simpler;
  ev.promoted = promoted;
  ev.penalty = BicPenalty(2.0 * promoted, observations.size());  // a centre gained, a focal lost
  return ev;
}

FocalCandidateScores ScoreFocalCandidates(const std::vector<double>& e_constant,
                                          const std::vector<std::vector<double>>& e_candidates,
                                          const std::vector<char>& ruled_out, int extra_parameters,
                                          double noise_floor) {
  std::vector<double> finite;
  for (const auto& e : e_candidates)
    for (double v : e)
      if (std::isfinite(v)) finite.push_back(v);
  FocalCandidateScores s;
  s.sigma = SigmaOf(finite, noise_floor);
  s.chi2_constant = CappedChi2(e_constant, s.sigma);
  s.penalty = BicPenalty(extra_parameters, e_constant.size());
  double best_chi2 = 0;
  for (size_t c = 0; c < e_candidates.size(); ++c) {
    s.chi2.push_back(CappedChi2(e_candidates[c], s.sigma));
    if (c + 1 < ruled_out.size() && ruled_out[c + 1]) continue;
    if (s.best < 0 || s.chi2[c] < best_chi2) {
      s.best = static_cast<int>(c);
      best_chi2 = s.chi2[c];
    }
  }
  if (s.best < 0) return s;
  const double bic1 = best_chi2 + s.penalty;
  if (!(bic1 < s.chi2_constant || (!ruled_out.empty() && ruled_out[0]))) s.best = -1;
  return s;
}

int ChooseFocalCandidate(const std::vector<double>& e_constant,
                         const std::vector<std::vector<double>>& e_candidates,
                         const std::vector<char>& ruled_out, int extra_parameters, double noise_floor) {
  return ScoreFocalCandidates(e_constant, e_candidates, ruled_out, extra_parameters, noise_floor).best;
}

BicComparison CompareByBic(const std::vector<double>& e_general, const std::vector<double>& e_simpler,
                           int extra_parameters, double noise_floor, const std::vector<double>& blur_sigma) {
  const Chi2Pair c = CappedChi2Pair(e_general, e_simpler, noise_floor, blur_sigma);
  BicComparison b;
  b.sigma = c.sigma;
  b.chi2_general = c.general;
  b.chi2_simpler = c.simpler;
  b.penalty = BicPenalty(extra_parameters, e_general.size());
  return b;
}

bool FitsAsWell(const std::vector<double>& e_reference, const std::vector<double>& e_candidate, double noise_floor) {
  const Chi2Pair c = CappedChi2Pair(e_reference, e_candidate, noise_floor, {});
  return c.simpler <= c.general + BicPenalty(1, e_reference.size());
}

}  // namespace hapcine
