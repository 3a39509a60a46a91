#include "estimate/window/zoom_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "estimate/window/dolly_or_zoom.h"
#include "estimate/window/window_freedoms.h"

namespace hapcine {
namespace {

// A margin as decisiveness: clamped to [0, 1], an infinite margin (no
// penalty to pay; no relief at all) saturating at 0 or 1. Not core's
// Clamp01, which maps every non-finite value to 0: a decision that costs
// nothing would read as undecided. NaN does not reach here (Decisiveness
// returns 0 for a NaN BIC margin; ReliefMargin maps a NaN relief to -inf).
double SaturatedMargin(double margin) { return std::clamp(margin, 0.0, 1.0); }

}  // namespace

double BicMargin(const ZoomDecision& d) {
  // Two branches with the same freedoms: no penalty to pay, the zoom's threshold is the unit.
  const double excess = d.test == "branch" ? d.gain : d.gain - d.penalty;
  if (d.penalty > 0) return excess / d.penalty;
  return excess >= 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

double ReliefMargin(const ZoomDecision& d) {
  if (d.relief < 0) return 0;
  if (!(d.relief > 0)) return -std::numeric_limits<double>::infinity();
  return std::log2(d.relief / kMinDollyRelief);
}

double Decisiveness(const ZoomDecision& d) {
  // Two branches always differ (they move opposite ways), however little they zoom.
  if ((d.zoom_change < kNegligibleLogZoom && d.test != "branch") || d.decided_by_cue) return 1;
  const double bic = BicMargin(d);
  if (std::isnan(bic)) return 0;
  // A branch's gain counts against its own spread over tracks too.
  if (d.test == "branch") {
    return std::min(SaturatedMargin(std::abs(bic)),
                    SaturatedMargin(std::abs(d.fit_z) / kBranchFitZ));
  }
  if (d.relief < 0) return SaturatedMargin(std::abs(bic));
  // Two gates: the dolly needs both, the zoom stays when either fails.
  const double relief = ReliefMargin(d);
  if (!d.zoom_taken) return std::min(SaturatedMargin(bic), SaturatedMargin(relief));
  return std::max(SaturatedMargin(-bic), SaturatedMargin(-relief));
}

bool IsDecisive(const ZoomDecision& d) { return Decisiveness(d) >= 1; }

bool IsAmbiguous(const ZoomDecision& d) { return Decisiveness(d) < kAmbiguousBelow; }

bool WindowZoomAmbiguous(const std::vector<ZoomDecision>& decisions) {
  return WindowDecisiveness(decisions) < kAmbiguousBelow;
}

// Only where the zoom is the added freedom (the focal choice, the freedom
// test): there the reading without zoom is also the simpler one. A dolly or
// a promotion to general adds a centre and a depth per point instead, which
// an ambiguous margin does not pay for (a telephoto zoom's tail taken as a
// dolly invents a translation).
bool PreferNoZoom(const ZoomDecision& d) {
  return d.zoom_taken && IsAmbiguous(d) && (d.test == "focal" || d.test == "freedoms");
}

double PairedBranchZ(int taken_agree, int taken_disagree, int other_agree, int other_disagree) {
  const double for_taken = taken_agree + other_disagree, against = taken_disagree + other_agree;
  return for_taken + against > 0 ? (for_taken - against) / std::sqrt(for_taken + against) : 0;
}

bool BranchDecidedByFit(const ZoomDecision& d) {
  return BicMargin(d) >= kAmbiguousBelow && d.fit_z >= kBranchFitZ;
}

bool PreferOtherBranch(const ZoomDecision& d, double other_zoom_change, double paired_z, int taken_floor,
                       int other_floor) {
  if (d.test != "branch") return false;
  if (std::abs(paired_z) >= kBranchOverruleZ) return paired_z < 0;
  if (BranchDecidedByFit(d)) return false;
  // On the wrong branch no floor is parallel to the move: a plane under one reading only tells.
  if ((taken_floor > 0) != (other_floor > 0)) return other_floor > 0;
  if (std::abs(paired_z) >= kBranchTieBreakZ) return paired_z < 0;
  return other_zoom_change < d.zoom_change;
}

double TrackPairedZ(const std::vector<double>& e_taken, const std::vector<double>& e_other,
                    const std::vector<int>& point_of_obs, double sigma) {
  auto capped = [sigma](double e) { return std::isfinite(e) ? std::min(e * e / (sigma * sigma), 9.0) : 9.0; };
  std::map<int, double> per_track;
  const size_t n = std::min({e_taken.size(), e_other.size(), point_of_obs.size()});
  for (size_t i = 0; i < n; ++i) per_track[point_of_obs[i]] += capped(e_other[i]) - capped(e_taken[i]);
  double sum = 0, sum_sq = 0;
  for (const auto& [point, d] : per_track) {
    sum += d;
    sum_sq += d * d;
  }
  return sum_sq > 0 ? sum / std::sqrt(sum_sq) : 0;
}

double WindowDecisiveness(const std::vector<ZoomDecision>& decisions) {
  double least = 1;
  for (const ZoomDecision& d : decisions) least = std::min(least, Decisiveness(d));
  return least;
}

double ZoomConfidenceFactor(const std::vector<ZoomDecision>& decisions) {
  return 1 - kAmbiguityDiscount * (1 - WindowDecisiveness(decisions));
}

double TotalLogZoom(const std::vector<BaCamera>& cams, const std::vector<char>& intervals) {
  double sum = 0;
  for (size_t i = 1; i < cams.size(); ++i)
    if (intervals.empty() || (i < intervals.size() && intervals[i]))
      sum += std::abs(cams[i].log_focal - cams[i - 1].log_focal);
  return sum;
}

}  // namespace hapcine
