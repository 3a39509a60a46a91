#pragma once
// Appearance check for KLT tracks: ends tracks whose patch no longer looks
// like the patch they were born on.
//
// Why: a KLT corner formed by a foreground silhouette against a background
// (a T-junction at an occlusion edge) slides smoothly and passes the
// forward-backward check, yet follows no 3-D point: as the background slides
// behind the edge the half of the patch off the foreground changes. A corner
// on one rigid surface changes only slowly (scale, perspective, lighting).
// The check keeps each track's patch at birth (zero-mean, unit-norm, sampled
// sub-pixel at the track position on the working image) and compares it by
// normalised cross-correlation (NCC) with the patch at the track's current
// position.

#include <deque>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <vector>

namespace hapcine {

// Zero-mean, unit-norm side x side patch of `gray` (CV_8UC1) centred on
// `at` (sub-pixel, OpenCV pixel-centre convention; outside pixels replicate
// the border). Returns false (and leaves *patch empty) for a flat patch,
// whose NCC says nothing.
bool NormalizedPatch(const cv::Mat& gray, cv::Point2f at, int side, cv::Mat* patch);

// NCC of two NormalizedPatch results, in [-1, 1].
double PatchNcc(const cv::Mat& a, const cv::Mat& b);

class AppearanceCheck {
 public:
  // reference_lag 0: every track is compared with its patch at birth;
  // K > 0: with its patch K scored frames ago (with the birth patch while
  // it is younger), which forgives slow change (zoom, perspective).
  explicit AppearanceCheck(int patch_side = 11, int reference_lag = 0)
      : side_(patch_side), lag_(reference_lag) {}

  // Scores the live tracks of one frame: (*ncc)[i] = NCC of track ids[i]'s
  // patch at points[i] with its reference patch. New ids record their birth
  // patch and score 1; so do tracks whose reference or current patch is
  // flat (no evidence either way). Ids not passed are forgotten (a track
  // that ended never comes back).
  void Score(const cv::Mat& gray, const std::vector<cv::Point2f>& points,
             const std::vector<long>& ids, std::vector<float>* ncc);
  // Records the birth patch of a new track (Score also does, for ids it
  // has not seen).
  void Born(const cv::Mat& gray, cv::Point2f at, long id);
  void Clear() { history_.clear(); }
  size_t size() const { return history_.size(); }

 private:
  int side_, lag_;
  // Per track: its reference patch first, then (lag_ > 0) the patches of
  // the frames since. An empty Mat is a flat patch.
  std::unordered_map<long, std::deque<cv::Mat>> history_;
};

}  // namespace hapcine
