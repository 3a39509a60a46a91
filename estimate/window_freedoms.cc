#include "estimate/window_freedoms.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"

namespace hapcine {
namespace {

// Median of |e| of a 2-D Gaussian residual = sigma sqrt(2 ln 2) = 1.1774 sigma.
double SigmaOf(const std::vector<double>& errors, double noise_floor) {
  return std::max(Median(errors, 0.0) / 1.1774, noise_floor);
}

double CappedChi2(const std::vector<double>& errors, double sigma) {
  double sum = 0;
  for (double v : errors) sum += std::isfinite(v) ? std::min(v * v / (sigma * sigma), 9.0) : 9.0;
  return sum;
}

}  // namespace

FreedomEvidence CompareFreedoms(const std::vector<BaCamera>& with_cams, const std::vector<BaPoint>& with_points,
                                const std::vector<BaCamera>& without_cams,
                                const std::vector<BaPoint>& without_points,
                                const std::vector<BaObservation>& observations,
                                const std::vector<char>& drop_translation, const std::vector<char>& drop_zoom,
                                double noise_floor) {
  FreedomEvidence ev;
  const std::vector<double> e_with = ObservationErrors(with_cams, with_points, observations, true);
  const std::vector<double> e_without = ObservationErrors(without_cams, without_points, observations, false);
  ev.sigma = SigmaOf(e_with, noise_floor);
  ev.chi2_with = CappedChi2(e_with, ev.sigma);
  ev.chi2_without = CappedChi2(e_without, ev.sigma);

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
  const double m = 2.0 * static_cast<double>(observations.size());
  ev.penalty = (3.0 * ev.translation_dropped + ev.zoom_dropped + ev.informed_points) * std::log(std::max(m, 2.0));
  return ev;
}

PromotionEvidence ComparePromotion(const std::vector<BaCamera>& promoted_cams,
                                   const std::vector<BaPoint>& promoted_points,
                                   const std::vector<BaCamera>& current_cams,
                                   const std::vector<BaPoint>& current_points,
                                   const std::vector<BaObservation>& observations,
                                   const std::vector<char>& promoted, const std::vector<char>& zoom_removed,
                                   double noise_floor) {
  PromotionEvidence ev;
  const std::vector<double> e_promoted = ObservationErrors(promoted_cams, promoted_points, observations, true);
  const std::vector<double> e_current = ObservationErrors(current_cams, current_points, observations, true);
  ev.sigma = SigmaOf(e_promoted, noise_floor);
  ev.chi2_promoted = CappedChi2(e_promoted, ev.sigma);
  ev.chi2_current = CappedChi2(e_current, ev.sigma);
  for (char c : promoted) ev.promoted += c != 0;
  for (char c : zoom_removed) ev.zoom_removed += c != 0;
  const double m = 2.0 * static_cast<double>(observations.size());
  ev.penalty = (3.0 * ev.promoted - ev.zoom_removed) * std::log(std::max(m, 2.0));
  return ev;
}

}  // namespace hapcine
