#pragma once
// How decisive a window's zoom decisions were (docs/estimate.md "Zoom or
// dolly: how decisive").
//
// Every zoom decision of a window is a BIC comparison between a model with a
// zoom and one without (window_freedoms.h, dolly_or_zoom.h): the freedoms of
// the more general model buy `gain` = chi2_simpler - chi2_general (capped,
// units of sigma^2) and cost `penalty` = k ln(2 m). The margin
//   (gain - penalty) / penalty
// is how far the evidence was from the threshold, in units of the threshold:
// at 0 a small change of the tracks flips the decision; at +-1 the freedoms
// buy twice their price, or nothing at all. The dolly-or-zoom test has a
// second gate, the dolly's depth relief against kMinDollyRelief: its margin is
// log2(relief / kMinDollyRelief), +-1 at twice or half the threshold.
//
// Decisiveness in [0, 1] is the margin of the gate that decided, clamped
// (|margin| >= 1: 1). A decision whose two readings differ by less than a
// visible zoom (sum |delta ln f| under kNegligibleLogZoom) is decisive
// whatever its margin: either reading gives the same picture. A branch cue
// (occlusion order, floor) that ruled the constant focal out decides too.
//
// A window's frames take the confidence factor 1 - kAmbiguityDiscount (1 - d),
// d its least decisive decision: 1 for decisive ones, down to 1/2 at a
// decision exactly on its threshold; continuous in the evidence, so the
// confidence does not jump between two nearly equal windows.
//
// The branch of the axial dolly/zoom ambiguity (test "branch"): where no cue
// ruled a branch out, the window's fit chose between readings that move
// opposite ways along the axis with the same freedoms, so there is no
// penalty to pay; `gain` is the capped chi2 by which the best reading of the
// other branch fits worse, and `penalty` the window's focal decision's
// (its zoom's threshold) as the unit: margin gain / penalty, 0 at a tie.
//
// Ambiguous: decisiveness under kAmbiguousBelow, the evidence within half a
// threshold of the other reading. There the reading without zoom is taken
// where it is also the simpler one (PreferNoZoom), and the shot quality
// summary counts the frames.

#include <string>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// The largest share of a frame's confidence an undecided zoom takes away.
constexpr double kAmbiguityDiscount = 0.5;
// A decision less decisive than this is ambiguous (above).
constexpr double kAmbiguousBelow = 0.5;

struct ZoomDecision {
  std::string test;         // "dolly_or_zoom", "focal", "promotion", "freedoms" or "branch"
  double gain = 0;          // chi2 the more general model's freedoms bought
  double penalty = 0;       // their BIC penalty k ln(2 m)
  bool zoom_taken = false;  // the window keeps (or takes) the zoom
  double zoom_change = 0;   // sum |delta ln f| of the zooming reading over the window
  double relief = -1;       // dolly_or_zoom: the dolly's depth relief (-1: no second gate)
  bool decided_by_cue = false;  // focal: a branch cue ruled out the constant focal
  double fit_z = 0;             // branch: the gain against its spread over tracks (TrackPairedZ)
};

// (gain - penalty) / penalty (a branch: gain / penalty); +-infinity with no penalty.
double BicMargin(const ZoomDecision& d);

// log2(relief / kMinDollyRelief); 0 without a relief gate.
double ReliefMargin(const ZoomDecision& d);

// In [0, 1]: how far the deciding gate was from its threshold (above).
double Decisiveness(const ZoomDecision& d);

bool IsDecisive(const ZoomDecision& d);

// Decisiveness < kAmbiguousBelow.
bool IsAmbiguous(const ZoomDecision& d);

// The least decisive of a window's decisions is ambiguous.
bool WindowZoomAmbiguous(const std::vector<ZoomDecision>& decisions);

// Where the evidence cannot tell, the reading without zoom is taken: true
// for an ambiguous decision that kept (or took) the zoom where the zoom is
// the added freedom (tests "focal" and "freedoms"; not "dolly_or_zoom" nor
// "promotion", whose reading without zoom adds a centre and a depth per
// point). The caller takes the other reading and records the decision with
// zoom_taken false (it stays ambiguous: its confidence is lowered all the
// same).
bool PreferNoZoom(const ZoomDecision& d);

// A cue under its own gate still tells a branch the fit left open: the
// occlusion order's paired sign test at one sigma (kBranchTieBreakZ).
constexpr double kBranchTieBreakZ = 1.0;

// Paired sign test of the occlusion votes of the two branches' readings
// (occlusion_order.h): the taken reading's agreeing and the other's
// disagreeing votes count for the taken branch, the rest against;
// (for - against) / sqrt(for + against), 0 without votes.
double PairedBranchZ(int taken_agree, int taken_disagree, int other_agree, int other_disagree);

// The fit decides a branch only where its gain is both half the zoom's
// threshold (BicMargin >= kAmbiguousBelow) and kBranchFitZ of its spread
// over tracks (fit_z, TrackPairedZ): unmodelled image effects that change
// with the zoom (a lens's barrel distortion, in pixels k1 r^3 / f^2, grows
// as the lens zooms out) are shared by a track's observations, so a gain
// summed over many observations may come from few tracks.
constexpr double kBranchFitZ = 2.0;
bool BranchDecidedByFit(const ZoomDecision& d);

// The occlusion order overrules the fit where its paired test reaches this:
// the paired test counts each event under both readings, so 2 sqrt(2) is the
// gate of 2 a single reading's votes need to rule a branch out.
constexpr double kBranchOverruleZ = 2.0 * 1.4142135623730951;

// Whether a branch decision takes the other branch's best reading: where
// the occlusion order's paired test reaches kBranchOverruleZ, the branch it
// favours. A decision the fit did not make besides: where a floor plane
// (plane_prior.h, >= 12 points) was found under one branch's reading only,
// that branch (on the wrong branch no floor is parallel to the move); else
// where the paired occlusion test reaches kBranchTieBreakZ either way, the
// branch it favours; else the reading with less zoom (sum |delta ln f|;
// `other_zoom_change` the other's). `*_floor`: each reading's plane support
// (0 or less: none found or not searched).
bool PreferOtherBranch(const ZoomDecision& d, double other_zoom_change, double paired_z, int taken_floor = 0,
                       int other_floor = 0);

// Paired test of two readings' fit, clustered by track: with d_j the sum
// over track j's observations of min(e_other^2 / sigma^2, 9) - min(e_taken^2
// / sigma^2, 9), z = sum_j d_j / sqrt(sum_j d_j^2) (positive: the taken
// reading fits better). Observations of one track share its tracking drift,
// so the track, not the observation, is the independent unit. 0 without
// any difference. `point_of_obs[i]`: observation i's track (point index).
double TrackPairedZ(const std::vector<double>& e_taken, const std::vector<double>& e_other,
                    const std::vector<int>& point_of_obs, double sigma);

// The least decisive of a window's decisions; 1 without any.
double WindowDecisiveness(const std::vector<ZoomDecision>& decisions);

// The factor a window's frames' confidence takes: in [1 - kAmbiguityDiscount, 1].
double ZoomConfidenceFactor(const std::vector<ZoomDecision>& decisions);

// sum_i |ln f_i - ln f_{i-1}| over the intervals i with `intervals[i]`
// (empty: every interval).
double TotalLogZoom(const std::vector<BaCamera>& cams, const std::vector<char>& intervals = {});

}  // namespace hapcine
