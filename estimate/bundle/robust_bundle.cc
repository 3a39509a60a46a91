#include "estimate/bundle/robust_bundle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/statistics.h"

namespace hapcine {

void PolishBundle(const BaOptions& options, std::vector<BaCamera>* cameras, std::vector<BaPoint>* points,
                  const std::vector<BaObservation>& observations, BaSummary* summary) {
  BaOptions polish = options;
  polish.max_iterations = std::max(5, options.max_iterations / 3);
  const BaSummary s = SolveBundle(cameras, points, observations, polish);
  summary->iterations += s.iterations;
  if (s.success) {
    summary->rms_after = s.rms_after;
    summary->num_observations = s.num_observations;
    summary->final_cost = s.final_cost;
    summary->termination = s.termination;
  }
}

BaSummary SolveDroppingOutliers(const BaOptions& options, std::vector<BaCamera>* cameras,
                                std::vector<BaPoint>* points, std::vector<BaObservation>* observations) {
  // 40 iterations without converging on the first window of a 1080p
  // sideways traveling at the usual tolerance, ~1e-5 a step.
  BaOptions first = options;
  first.function_tolerance = 1e-4;
  BaSummary s = SolveBundle(cameras, points, *observations, first);
  if (!s.success) return s;
  const auto errs = ObservationErrors(*cameras, *points, *observations, options.use_depth);
  std::vector<BaObservation> kept;
  for (size_t i = 0; i < observations->size(); ++i)
    if (std::isfinite(errs[i]) && errs[i] < 1.5 * options.huber_scale) kept.push_back((*observations)[i]);
  const bool polish_follows = kept.size() < observations->size() && kept.size() > 10;
  if (!polish_follows && first.function_tolerance != options.function_tolerance) {
    BaOptions rest = options;
    rest.max_iterations = std::max(1, options.max_iterations - s.iterations + 1);
    const BaSummary s3 = SolveBundle(cameras, points, *observations, rest);
    s.iterations += s3.iterations;
    if (s3.success) {
      s.rms_after = s3.rms_after;
      s.final_cost = s3.final_cost;
      s.termination = s3.termination;
    }
  }
  if (polish_follows) {
    *observations = kept;
    PolishBundle(options, cameras, points, *observations, &s);
  }
  return s;
}

void DropInconsistentTracks(const BaOptions& options, double floor_cut, std::vector<BaCamera>* cameras,
                            std::vector<BaPoint>* points, const std::vector<BaObservation>& all,
                            std::vector<BaObservation>* kept, BaSummary* summary) {
  *kept = all;
  for (double factor : {2.5, 2.0, 1.5, 1.0}) {
    const auto errs = ObservationErrors(*cameras, *points, *kept, options.use_depth);
    std::vector<double> sum_sq(points->size(), 0);
    std::vector<int> count(points->size(), 0);
    for (size_t i = 0; i < kept->size(); ++i) {
      const int k = (*kept)[i].point;
      sum_sq[k] += std::isfinite(errs[i]) ? errs[i] * errs[i] : std::numeric_limits<double>::infinity();
      ++count[k];
    }
    std::vector<double> rms(points->size(), 0), finite;
    for (size_t k = 0; k < points->size(); ++k) {
      if (!count[k]) continue;
      rms[k] = std::sqrt(sum_sq[k] / count[k]);
      if (std::isfinite(rms[k])) finite.push_back(rms[k]);
    }
    if (finite.empty()) break;
    const double cut = factor * std::max(floor_cut, 2.0 * Quantile(std::move(finite), 0.25));
    std::vector<BaObservation> next;
    for (const auto& o : *kept)
      if (rms[o.point] < cut) next.push_back(o);
    if (next.size() <= 10) break;
    *kept = next;
    PolishBundle(options, cameras, points, *kept, summary);
  }
}

}  // namespace hapcine
