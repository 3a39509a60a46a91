#include "estimate/window/track_drift.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace hapcine {

std::vector<int> ObservationAges(const std::vector<BaObservation>& observations, const std::vector<int>& keyframe_pos) {
  std::map<int, int> first_pos;  // point -> frame position of its earliest observation
  for (const auto& o : observations) {
    const int pos = keyframe_pos[o.camera];
    auto [it, inserted] = first_pos.emplace(o.point, pos);
    if (!inserted) it->second = std::min(it->second, pos);
  }
  std::vector<int> ages;
  ages.reserve(observations.size());
  for (const auto& o : observations) ages.push_back(keyframe_pos[o.camera] - first_pos[o.point]);
  return ages;
}

DriftFit FitDrift(const std::vector<double>& errors, const std::vector<int>& ages) {
  DriftFit fit;
  double n = 0, sx = 0, sy = 0;
  for (size_t i = 0; i < errors.size() && i < ages.size(); ++i) {
    if (!std::isfinite(errors[i])) continue;
    n += 1;
    sx += ages[i];
    sy += errors[i] * errors[i];
  }
  fit.observations = static_cast<int>(n);
  if (n < 3) return fit;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < errors.size() && i < ages.size(); ++i) {
    if (!std::isfinite(errors[i])) continue;
    sxx += (ages[i] - mx) * (ages[i] - mx);
    sxy += (ages[i] - mx) * (errors[i] * errors[i] - my);
  }
  if (!(sxx > 0)) return fit;  // one age only: no growth to measure
  fit.q_sq = sxy / sxx;
  fit.s0_sq = my - fit.q_sq * mx;
  double rss = 0;
  for (size_t i = 0; i < errors.size() && i < ages.size(); ++i) {
    if (!std::isfinite(errors[i])) continue;
    const double r = errors[i] * errors[i] - fit.s0_sq - fit.q_sq * ages[i];
    rss += r * r;
  }
  const double se = std::sqrt(rss / (n - 2) / sxx);
  fit.t_slope = se > 0 ? fit.q_sq / se : (fit.q_sq > 0 ? INFINITY : 0);
  fit.significant = fit.s0_sq > 0 && fit.q_sq > 0 && fit.t_slope >= kDriftMinT;
  return fit;
}

bool ApplyDriftWeights(const DriftFit& fit, const std::vector<int>& ages, std::vector<BaObservation>* observations) {
  if (!fit.significant) return false;
  const double growth = fit.q_sq / fit.s0_sq;
  for (size_t i = 0; i < observations->size() && i < ages.size(); ++i)
    (*observations)[i].noise_scale = std::sqrt(1 + growth * ages[i]);
  return true;
}

}  // namespace hapcine
