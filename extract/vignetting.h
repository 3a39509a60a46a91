#pragma once
// Vignetting: a lens darkens its picture towards the corners by a fixed
// multiplicative field V(rho), rho the distance from the picture's centre
// over the centre-to-corner distance. A tracked point moving from rho1 to
// rho2 changes brightness by V(rho2) / V(rho1), and the field's slope inside
// a KLT window does not move with the texture: LK (brightness constancy)
// reads the motion short where the fall-off is steep, at the picture's
// edges, and a rotation's focal comes out long (docs/extract.md
// "Vignetting").
//
// VignettingFit estimates log V = a rho^2 + b rho^4 from tracked pairs: the
// log brightness change of each pair against its change of rho^2 and rho^4,
// with one exposure offset per frame step (fades, auto exposure), by
// iteratively reweighted least squares (Huber). It decides for a field only
// when the data demand one (Decide): a darkening at the corner of at least
// kMinCornerFalloff, many standard errors from zero. FlatFieldGain /
// FlatFielded divide a frame by the field.

#include <opencv2/core.hpp>
#include <vector>

namespace hapcine {

struct VignettingModel {
  double a = 0, b = 0;  // log V(rho) = a rho^2 + b rho^4
  bool found = false;   // the data demanded a field
  double corner_gain() const;  // V(1): brightness at the corner over the centre's
};

// A field darker than this at the corner (5 %) is kept: below it, the
// shortfall it causes (a fraction of the fall-off's share of the
// brightness change across a window) is within KLT's own noise.
constexpr double kMinCornerFalloff = 0.05;
// Once a field is taken, what is left of it is added when it reaches this
// at the corner (either way), up to kMaxVignettingRefinements fields.
constexpr double kMinResidualFalloff = 0.01;
constexpr int kMaxVignettingRefinements = 6;
// ... and at least this many standard errors of the fit from no field.
constexpr double kMinFalloffSigmas = 8;
// Pairs (with a change of rho^2 of at least kMinRadialMove) before a decision.
constexpr size_t kMinVignettingPairs = 400;
constexpr double kMinRadialMove = 0.01;
// The fit stops taking pairs here (its standard error is far below the
// fall-off worth correcting long before).
constexpr size_t kMaxVignettingPairs = 40000;

class VignettingFit {
 public:
  // One frame step: the tracks' positions `from` (in `before`) and `to` (in
  // `after`), pixels of a picture of `size`; `before` / `after` are smoothed
  // copies of the two frames at 1 / `scale` of that size (a pyramid level),
  // where the local brightness is read. Dark, saturated and radially still
  // pairs carry no evidence and are skipped.
  void AddStep(const cv::Mat& before, const cv::Mat& after, double scale, const std::vector<cv::Point2f>& from,
               const std::vector<cv::Point2f>& to, cv::Size size);
  // The field, found only where the data demand one: a darkening at the
  // corner of `min_falloff` or more (any change once a field is taken:
  // `min_falloff` below kMinCornerFalloff), many standard errors from none.
  VignettingModel Decide(double min_falloff = kMinCornerFalloff) const;
  size_t pairs() const { return pairs_.size(); }
  bool full() const { return pairs_.size() >= kMaxVignettingPairs; }

 private:
  struct Pair {
    int step;
    float d_rho2, d_rho4, d_log;  // changes of rho^2, rho^4 and log brightness
  };
  std::vector<Pair> pairs_;
  int steps_ = 0;
};

// Per-pixel gain that undoes `model` on a picture of `size`, CV_32F, scaled
// so that its largest value is 1 (the centre is darkened to the corner's
// level rather than the corners brightened past white).
cv::Mat FlatFieldGain(const VignettingModel& model, cv::Size size);
// `gray` (CV_8UC1) times `gain`, rounded.
cv::Mat FlatFielded(const cv::Mat& gray, const cv::Mat& gain);

}  // namespace hapcine
