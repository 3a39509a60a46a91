#pragma once
// Affine Lucas-Kanade of one patch against its first appearance (Shi and
// Tomasi's feature monitoring): a patch of an anchor image, aligned in a
// later image by an affine warp and a gain and bias. Frame-to-frame KLT
// only follows a translation, so as the view turns the patch changes
// shape and the track slides a little every frame; the affine warp
// follows the change of shape, and the normalised residual says how well
// the patch still matches its first appearance.

#include <opencv2/core.hpp>

namespace hapcine {

struct AffinePatchFit {
  cv::Point2f position;                        // where the anchor point is in the image
  cv::Matx22f linear = cv::Matx22f::eye();     // image offset per anchor offset
  float residual = 0;  // RMS of the photometric residual / the matched patch's RMS contrast
  bool ok = false;     // inside the image, not flat, area changed by less than 4x
  bool inside = true;  // false: a window left its image (nothing measured, no evidence either way)
};

// Aligns the (2 half_window + 1)^2 patch of `anchor_image` centred at
// `anchor` to `image` (both CV_8UC1), starting from `start` (position and
// linear part, e.g. the KLT position and the track's last fit). Gauss-Newton
// in the forward-compositional form, at most `max_iterations`, stopping once
// the centre moves by less than `min_step_px`.
AffinePatchFit AlignAffinePatch(const cv::Mat& anchor_image, cv::Point2f anchor, const cv::Mat& image,
                                const AffinePatchFit& start, int half_window, int max_iterations = 20,
                                float min_step_px = 0.01f);

}  // namespace hapcine
