#pragma once
// The focal a shot's first translating window starts from, where no pair of
// frames turned without translating (those calibrate it by a rotation fit).
//
// The keyframes' two-view chain is built at the focal of the moment (the
// prior): every interval's essential matrix and the rotation it gives assume
// it. At a wrong focal the rotations are wrong by a factor and the chained
// poses do not agree with each other over the window (a point triangulated
// from two keyframes misses the others by tens of pixels); the bundle
// adjustment then stops in a minimum near the wrong focal and a per-keyframe
// focal "pays" by drifting towards the right one (a zoom invented on a
// fixed lens). Over the window the focal is observable once the solve is in
// its basin (a car's camera: from a start at 70-110 degrees of view the
// solve reaches 82 +- 2, from 60 it stops at 68): so the chain is rebuilt at
// a few focal lengths, each solved, and the best fit taken. The chain's own
// consistency is no guide: it drifts over tens of keyframes at any focal.

#include <set>
#include <vector>

#include "estimate/bundle/bundle_adjustment.h"
#include "estimate/window/window_solver.h"

namespace hapcine {

// The keyframes' cameras rebuilt with every log focal + `log_shift`: each
// free interval's relative pose fitted again from the tracks both keyframes
// see (not in `outliers`) at those focal lengths (translating: eight-point
// essential matrix on all of them, decomposed, translation scaled so that
// the median triangulated depth is `scene_depth`; rotating: Kabsch; else the
// identity). Held keyframes keep their pose; an interval whose fit fails
// keeps its relative pose.
std::vector<BaCamera> ChainAtFocal(const std::vector<WindowKeyframe>& keyframes, double log_shift,
                                   const std::set<long>& outliers, double scene_depth);

// The starts a shot's first calibrating window is solved from: the chain at
// the prior focal (shift 0) and at the prior x 2^(-1/2) and x 2^(1/2)
// (log shifts). Measured reach with the prior at 50 degrees: a real car's
// 82 degrees is found (2 % long); a synthetic street at 88 degrees is not
// (the solve stays near its 67 degree start) but invents no zoom either.
std::vector<double> FocalStartShifts();

// Which start's solve to take: `errors[s]` its reprojection errors on the
// window's observations (ObservationErrors), errors[0] the prior's. Capped
// chi2 (sum min(e^2 / sigma^2, 9), one sigma = median / 1.1774 of all, at
// least `noise_floor`); the solves have the same freedoms, and one whose
// chi2 is not below the prior's by one parameter's BIC penalty ln(2 m) is
// no evidence against the prior. Returns the index taken.
int BestFocalStart(const std::vector<std::vector<double>>& errors, double noise_floor);

}  // namespace hapcine
