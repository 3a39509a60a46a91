#pragma once
// Do a window's few translating (and zooming) keyframe intervals pay for
// their freedoms? A test over all the window's keyframes at once, for windows
// where only a few intervals among rotation read as translating: the blur of
// a whip pan, a fading picture.
//
// The two-view test (model_selection.h) sees one pair of frames: where the
// tracking noise is larger along one direction (motion blur), an essential
// matrix whose epipolar lines run along it lets every match slide along the
// line and reads the noise as translation. Over several keyframes real
// parallax is explained by one depth per point for every interval, while
// noise changes from frame to frame: a bundle adjustment with translation
// then fits little more than one without it.
//
// The criterion is BIC on the window's reprojection errors, with one noise
// sigma measured from the solve with the freedoms:
//   chi2 = sum_i min(e_i^2 / sigma^2, 9)
//   the freedoms pay off  <=>  chi2_without - chi2_with > k ln(2 m)
// with m observations and k the parameters they add: a centre (3) per
// keyframe that loses its translation, a focal (1) per keyframe that loses
// its zoom, and an inverse depth (1) per point whose observations span an
// interval that loses its translation (the other points' depths are not
// observed by it).

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

// A zoom-only test also drops a zoom whose total change over the tested
// intervals (sum of |delta ln f| in the solve with it) is under this: 0.1 %,
// a fifth of the zoom-ratio accuracy the estimator aims at, is no zoom a
// viewer sees, however well the tracks support it (a slow tilt can read as
// a 0.007 % zoom that fits better than none).
constexpr double kNegligibleLogZoom = 1e-3;

// Motion blur: KLT on a blurred corner is off along the blur by an amount
// that depends on the corner's texture and lasts while the blur does (a bias
// per track that a small move there and back with one depth per track fits).
// The blur grows with the image speed, so each observation's noise is taken
// as sigma^2 + (per_speed * speed)^2, speed = the point's image motion per
// frame to its neighbouring observations in the window (normalised units).
// Returns per_speed * speed per observation (0 for a point seen once).
std::vector<double> BlurSigmas(const std::vector<BaObservation>& observations,
                               const std::vector<int>& frame_of_camera, double per_speed);

struct FreedomEvidence {
  double chi2_with = 0, chi2_without = 0;  // capped, in units of sigma^2
  double penalty = 0;                      // k ln(2 m)
  double sigma = 0;                        // normalised units
  int translation_dropped = 0, zoom_dropped = 0, informed_points = 0;
  double zoom_change = 0;                  // sum |delta ln f| over the intervals losing their zoom
  bool PaysOff() const {
    const bool negligible_zoom_only = translation_dropped == 0 && zoom_change < kNegligibleLogZoom;
    return chi2_without - chi2_with > penalty && !negligible_zoom_only;
  }
};

// `with_*`: the window solved with every freedom (points with inverse depth);
// `without_*`: solved with the dropped freedoms shared with the previous
// keyframe, without translation anywhere (points as bearings).
// `observations` index both (all of the window's, outliers included: the cap
// bounds them). `drop_translation[i]` / `drop_zoom[i]`: the interval ending
// at camera i has that freedom in the `with` solve and not in the other.
// `noise_floor`: the smallest sigma, normalised units. `blur_sigma`: per
// observation, noise added to sigma in quadrature (BlurSigmas; empty: none).
FreedomEvidence CompareFreedoms(const std::vector<BaCamera>& with_cams, const std::vector<BaPoint>& with_points,
                                const std::vector<BaCamera>& without_cams,
                                const std::vector<BaPoint>& without_points,
                                const std::vector<BaObservation>& observations,
                                const std::vector<char>& drop_translation, const std::vector<char>& drop_zoom,
                                double noise_floor, const std::vector<double>& blur_sigma = {});

// The other way: in a window with translation, do its intervals labelled as
// a zoom without translation (zoom, rotation+zoom: a pair of frames reads the
// slow start of a forward dolly as a zoom) fit better as general
// (translation instead of the zoom)? Both solves have inverse depths; k = 3
// - 1 = 2 per promoted keyframe (a centre gained, a focal lost).
struct PromotionEvidence {
  double chi2_current = 0, chi2_promoted = 0;  // capped, units of sigma^2
  double penalty = 0;                          // k ln(2 m)
  double sigma = 0;                            // from the promoted solve, normalised units
  int promoted = 0;
  bool PaysOff() const { return chi2_current - chi2_promoted > penalty; }
};

// `promoted`: how many keyframes the promoted solve turned from a zoom into general.
PromotionEvidence ComparePromotion(const std::vector<BaCamera>& promoted_cams,
                                   const std::vector<BaPoint>& promoted_points,
                                   const std::vector<BaCamera>& current_cams,
                                   const std::vector<BaPoint>& current_points,
                                   const std::vector<BaObservation>& observations, int promoted,
                                   double noise_floor, const std::vector<double>& blur_sigma = {});

// A general window's per-keyframe focal (zoom in every general interval):
// does a candidate solved with it pay for itself against the constant-focal
// solve? `e_constant`, `e_candidates[c]`: each solve's errors on the same
// observations (ObservationErrors); sigma from all candidates' finite errors
// (median / 1.1774, at least `noise_floor`), chi2 capped as above. The
// candidate with the lowest chi2 among those not `ruled_out[c + 1]`
// (ruled_out[0]: the constant-focal solve) is taken if its chi2 +
// `extra_parameters` ln(2 m) is below the constant solve's, or if the
// constant solve is ruled out. Returns its index, or -1 (keep the constant focal).
int ChooseFocalCandidate(const std::vector<double>& e_constant,
                         const std::vector<std::vector<double>>& e_candidates,
                         const std::vector<char>& ruled_out, int extra_parameters, double noise_floor);
// The same with its scores (the window report): chi2 of the constant solve
// and of each candidate (ruled out or not), the penalty a candidate pays,
// and the choice (`best`: ChooseFocalCandidate's answer).
struct FocalCandidateScores {
  double sigma = 0, chi2_constant = 0, penalty = 0;
  std::vector<double> chi2;
  int best = -1;
};
FocalCandidateScores ScoreFocalCandidates(const std::vector<double>& e_constant,
                                          const std::vector<std::vector<double>>& e_candidates,
                                          const std::vector<char>& ruled_out, int extra_parameters,
                                          double noise_floor);

// Two fits of the same observations by BIC, as above: capped chi2 of each
// with one sigma from the more general fit's errors (`e_general`), and the
// penalty of its `extra_parameters`.
struct BicComparison {
  double sigma = 0, chi2_general = 0, chi2_simpler = 0, penalty = 0;
  bool GeneralPaysOff() const { return chi2_simpler - chi2_general > penalty; }
};
BicComparison CompareByBic(const std::vector<double>& e_general, const std::vector<double>& e_simpler,
                           int extra_parameters, double noise_floor, const std::vector<double>& blur_sigma = {});

// A candidate that moved along a direction the images leave open (a prior
// chose it) must fit about as well as the solve it came from: its capped
// chi2 (sigma from the reference's errors) at most one parameter's BIC
// penalty above the reference's. Otherwise the data disagree with the prior.
bool FitsAsWell(const std::vector<double>& e_reference, const std::vector<double>& e_candidate, double noise_floor);

}  // namespace hapcine
