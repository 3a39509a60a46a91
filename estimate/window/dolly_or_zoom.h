#pragma once
// A zoom or a dolly? The test for windows labelled without translation whose
// intervals zoom.
//
// A pair of keyframes a few frames apart cannot tell a slow push-in from a
// zoom: the parallax between near and far points grows with the distance
// travelled, and over one interval it is under the tracking noise, so the
// two-view selection (model_selection.h) takes the model with fewer
// parameters, a zoom. Over a window the same parallax adds up (a 0.2 m push-in
// towards a background 5-17 m away scales it by 4 % and by 1.2 %: a zoom
// leaves pixels of residual at the border). So the window is also solved as a
// dolly at a fixed lens (every moving interval general, the focal of the
// window's held keyframe, one inverse depth per point) and BIC on the
// window's reprojection errors decides:
//   chi2 = sum_i min(e_i^2 / sigma^2, 9), sigma from the dolly's errors
//   the dolly wins  <=>  chi2_zoom - chi2_dolly > k ln(2 m)
// with k the parameters the dolly adds: a centre (3) per interval that gains
// a translation, an inverse depth (1) per point whose observations span a
// translating interval, minus
// a focal (1) per interval that loses its zoom and minus one for the scale
// (not observable). A scene without depth relief (a wall facing the camera)
// gives the dolly nothing to fit better: the zoom stays, as it should where
// the images cannot tell.
//
// BIC counts every observation as independent, but KLT's error under a
// changing scale is not: a translation-only tracker drifts on a growing or
// shrinking corner by a share of the scaling, the same way over the track's
// life, and one inverse depth per point fits that drift as parallax (on the
// zoom presets the dolly beats the zoom by BIC with every point at the same
// depth to +-1 %, a flat scene 0.5 depth away). A dolly's parallax is the
// spread of its inverse depths times the scaling, the drift a fraction of the
// scaling: so the dolly is also asked for depth relief, its points' inverse
// depths spanning (10th to 90th percentile) at least kMinDollyRelief of their
// median (a background from 5 to 8 m). Less relief than that is a zoom.

#include <vector>

#include <Eigen/Core>

#include "estimate/window/window_solver.h"

namespace hapcine {

// The depth relief a dolly must show (above; measured on the zoom presets'
// dolly solves: 0.02-0.28).
constexpr double kMinDollyRelief = 0.5;

// Depth relief of points (x, y, w) (InverseDepthsIn): the spread of the
// inverse depths w from the 10th to the 90th percentile over their median;
// 0 without points or with a median at infinity.
double DepthRelief(const std::vector<Eigen::Vector3d>& xyw);

// The window as a dolly: every free interval that moves (not static, not a
// chain start) becomes general (a zoom interval's rotation stays shared,
// DollyStart). Empty when the window already translates
// somewhere or no free interval zooms (nothing to test).
std::vector<MotionModel> DollyLabels(const std::vector<WindowKeyframe>& keyframes);

// The dolly's start from the zoom solution `zoom` (solved cameras, the same
// keyframes): every keyframe after `held` keeps its rotation (and shares it
// where the zoom did: the two differ only in translation against zoom), takes the held
// keyframe's focal and moves along its own optical axis by
// depth (1 - f_held / f_k), so that a point at `depth` scales as the zoom
// scaled it (Z / (Z - t) = f_k / f_held). `shared`: the dolly's cameras
// (WindowCameras with DollyLabels: sharing and held flags), whose poses are
// replaced. Keyframes up to `held` are kept as they are in `shared`.
std::vector<BaCamera> DollyStart(const std::vector<BaCamera>& shared, const std::vector<BaCamera>& zoom, int held,
                                 double depth);

// k of the test above: `zoom_labels` the window's labels, `dolly_labels`
// DollyLabels, `observations` the window's (point and camera indices).
int DollyExtraParameters(const std::vector<MotionModel>& zoom_labels, const std::vector<MotionModel>& dolly_labels,
                         const std::vector<BaObservation>& observations);

}  // namespace hapcine
