#pragma once
// Labels the segments of a camera path with the camera effect of Table 1
// (or none) from the motion alone, so that semantic tracks can be made for
// films nobody authored.
//
// 1. Motion energy per frame, in "image radians per second" so that the
//    three kinds of motion are comparable:
//      translation |dp/dt| / D   (D = reference depth: a lateral move of D
//                                 shifts the image like a 1 rad turn)
//      rotation    angular speed of the camera (rad/s)
//      zoom        |d/dt ln(tan(fov0/2) / tan(fov/2))|
//    energy = the largest of the three, each measured as the net change over
//    a window of smoothing_s centred on the frame divided by its duration
//    (zero-mean jitter of an estimate cancels instead of adding up).
// 2. Segments: runs of frames inside a shot with energy > energy_threshold,
//    gaps shorter than merge_gap_s merged, runs shorter than min_segment_s
//    dropped.
// 3. Label from the net change over the segment (relative to its start):
//      vertigo   forward travel and zoom-out (or backward and zoom-in), both
//                significant, within a factor 20 of each other (their ratio
//                depends on the unknown subject distance), z and zoom
//                correlated (Pearson > 0.8)
//      zoom_in   zoom dominant (a zoom-out is zoom_in with intensity -1)
//      arcing    lateral travel with a compensating pan (moving right while
//                turning left keeps a subject in front framed)
//      then the dominant of translation vs rotation:
//      crane_shot  vertical travel dominant      traveling  lateral travel
//      zoom_in     forward/backward dolly (the paper treats a zoom as a
//                  forward movement, so a dolly gets the same metaphor)
//      tilting   tilt dominant   dutch_angle  roll dominant
//      traveling pan dominant (a pan follows an actor like a traveling)
//    Significant = at least significant_change (image radians).
//    intensity = +-1: the sign gives the direction (right/left, up/down,
//    forward/backward, counter-clockwise roll, tilt up).

#include <vector>

#include "core/camera_path.h"
#include "haptics/semantic_model.h"

namespace hapcine {

struct ClassifierOptions {
  double reference_depth_u = 0;      // 0: automatic, as in CinematicOptions
  double energy_threshold = 0.01;    // image radians per second
  double smoothing_s = 0.5;          // window of the energy, seconds
  double merge_gap_s = 0.3;          // merge runs separated by less
  double min_segment_s = 0.5;        // drop shorter runs
  double significant_change = 0.02;  // image radians over a segment
  void Check() const;                // throws UsageError
};

struct ClassifiedSegment {
  EffectSegment segment;
  // Net changes over the segment (image radians; signed).
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // dp / D, seat axes
  double tilt_rad = 0, pan_rad = 0, roll_rad = 0;
  double log_zoom = 0;
  double z_zoom_correlation = 0;  // Pearson corr(z, log_zoom) over the segment
};

std::vector<ClassifiedSegment> ClassifyCameraPath(const CameraPath& path,
                                                  const ClassifierOptions& options);
// Just the segments (for the semantic model).
std::vector<EffectSegment> ClassifyEffects(const CameraPath& path,
                                           const ClassifierOptions& options);

}  // namespace hapcine
