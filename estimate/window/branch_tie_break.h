#pragma once
// Who decides the branch of an axial dolly zoom when the fit does not
// (docs/estimate.md "The branch of an axial dolly zoom").

#include "estimate/window/zoom_evidence.h"

namespace hapcine {

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
// favours. A decision the fit did not make besides: where a floor plane (plane_prior.h, >= 12 points) was found
// under one branch's reading only, that branch (on the wrong branch no floor
// is parallel to the move); else where the paired occlusion test reaches
// kBranchTieBreakZ either way, the branch it favours; else the reading with
// less zoom (sum |delta ln f|; `other_zoom_change` the other's). `*_floor`:
// each reading's plane support (0 or less: none found or not searched).
bool PreferOtherBranchGivenFloor(const ZoomDecision& d, double other_zoom_change, double paired_z, int taken_floor,
                                 int other_floor);

}  // namespace hapcine
