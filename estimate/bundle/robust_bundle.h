#pragma once
// The robust rounds around SolveBundle that every window runs: a first solve,
// then observations the fit cannot explain dropped and the rest polished; and,
// after the window's model choice, whole tracks that no rigid point explains
// dropped in rounds (docs/estimate.md, "Algorithm", step 4).

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// Re-solves on `observations` (a reduced set), from the current, already
// close estimate with a third of the iterations (at least 5); a success
// updates `summary`'s RMS, observation count, final cost and termination
// (its iterations are added either way).
void PolishBundle(const BaOptions& options, std::vector<BaCamera>* cameras, std::vector<BaPoint>* points,
                  const std::vector<BaObservation>& observations, BaSummary* summary);

// Solves, drops the observations beyond 1.5 Huber scales (~1.5 px at 960 px)
// from `observations`, and polishes on the rest. The first solve stops at a
// 1e-4 relative decrease of the cost: with the outliers still in, its last
// iterations creep (the Huber loss converges linearly) towards a fit the
// polish redoes without them; when nothing is dropped it goes on to
// `options.function_tolerance`.
BaSummary SolveDroppingOutliers(const BaOptions& options, std::vector<BaCamera>* cameras,
                                std::vector<BaPoint>* points, std::vector<BaObservation>* observations);

// Whole-track rejection: a point whose reprojection RMS over all its
// observations in `all` exceeds the cut is dropped with every observation,
// and the window polished. The cut is max(`floor_cut`, 2x the lower quartile
// of the points' RMS) (normalised units; the quartile is about the noise of a
// good track), and it tightens over four rounds, 2.5x, 2x, 1.5x, 1x, each
// followed by a polish: the first solution is still bent by the bad tracks,
// and cutting tight at once also drops good tracks the bend put far.
// `kept`: the observations left (all of `all` when nothing is dropped).
void DropInconsistentTracks(const BaOptions& options, double floor_cut, std::vector<BaCamera>* cameras,
                            std::vector<BaPoint>* points, const std::vector<BaObservation>& all,
                            std::vector<BaObservation>* kept, BaSummary* summary);

}  // namespace hapcine
