#pragma once
// How well a solved window pins its focal: the profile of the fit along
// log f (docs/estimate.md, "kitti07: how well a window pins its focal").
//
// The window's focal is moved by a few log shifts and held there while
// everything else is solved again on the same observations; the chi2 of
// each (in units of the unshifted solve's residual variance) is fitted by a
// parabola in the shift. Its curvature a gives the focal's standard error
// under independent Gaussian residuals, sigma(log f) = 1 / sqrt(a)
// (chi2 rises by 1 at one sigma), and its minimum where the window's own
// evidence puts the focal given its held keyframes (in a later window,
// whose focal is held from the lead-in, that is the focal the window would
// take). Diagnostics: it costs one solve per shift, so only on request.

#include <vector>

#include "estimate/bundle/bundle_adjustment.h"

namespace hapcine {

struct FocalProfile {
  std::vector<double> log_shifts;  // the shifts solved (0 included)
  std::vector<double> chi2;        // sum e^2 / sigma0^2 per shift (NaN: the solve failed)
  double curvature = 0;            // a of chi2 ~ a s^2 + b s + c (<= 0: not pinned)
  double sigma_log_focal = 0;      // 1 / sqrt(a); +inf when a <= 0
  double minimum_log_shift = 0;    // -b / (2 a) (0 when a <= 0)
  // Per shift, every observation's residual (normalised units over its noise_scale): which
  // tracks pull the focal which way.
  std::vector<std::vector<double>> errors;
};

// The parabola is fitted to the shifts within +-this (log f): about the
// focal error that matters (a 2.7 % short focal lengthens a 96 degree turn
// by 1.5 degrees) and inside the fit's quadratic range.
constexpr double kFocalProfileFitHalfWidth = 0.02;

// The log shifts `ProfileFocal` solves by default: +-1 %, +-2 % (fitted), and
// -4 %, +3 %, +4 % (a second minimum within a few per cent shows there).
std::vector<double> DefaultFocalProfileShifts();

// The profile of a solved window (`cameras`, `points` solved on
// `observations`). Every camera's log focal is shifted and held (shared
// blocks move together, the held lead-in's too); the poses that were held
// stay held. `ba`: the window's solve options. The chi2 unit is the solve's
// own mean square residual (the textbook estimate of the noise variance; no
// floor: exact tracks pin the focal exactly).
FocalProfile ProfileFocal(const BaOptions& ba, const std::vector<BaCamera>& cameras,
                          const std::vector<BaPoint>& points, const std::vector<BaObservation>& observations,
                          const std::vector<double>& log_shifts);

// Sum of the squares of the finite values of `e` (a failed residual, NaN
// or infinite, counts 0): the chi2 numerator of a profile shift.
double SumOfFiniteSquares(const std::vector<double>& e);

// The parabola through (x, y) by least squares: a, b (and c) of y = a x^2 + b x + c.
// Needs three distinct x; returns false otherwise.
bool FitParabola(const std::vector<double>& x, const std::vector<double>& y, double* a, double* b, double* c);

}  // namespace hapcine
