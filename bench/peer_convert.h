#pragma once
// Turning what the OpenCV peers measure into camera-path frames
// (docs/formats.md), so `hapcine eval` scores them like hapcine:
//  - the stitching module's cameras: `R` is world_from_cam in OpenCV camera
//    axes (+X right, +Y down, +Z forward: a pixel's ray in the world is
//    R * K^-1 * [u v 1]), plus a focal length in pixels;
//  - videostab's accumulated 2-D similarity (pixels of frame 0 -> pixels of
//    frame i), read as a rotating and zooming camera about the image centre.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/camera_path.h"

namespace hapcine::bench {

// world_from_cam of camera `i` relative to camera `first`, both given in
// OpenCV axes, expressed in the file's OpenGL axes (F R F, F = diag(1,-1,-1)).
Eigen::Quaterniond RelativeRotationGl(const Eigen::Matrix3d& world_from_first_cv,
                                      const Eigen::Matrix3d& world_from_i_cv);

// Camera motion read off a 2-D similarity `frame0_to_i` (3x3, pixel
// coordinates, y down) of an image `width` x `height` whose frame 0 has focal
// `focal0_px`:
//  - scale s: focal_i = s * focal0 (zoom);
//  - rotation a of the image content (clockwise on screen for a > 0) is the
//    camera's roll (positive roll turns the content clockwise);
//  - the point at the centre of frame 0 lands at (tx, ty) from the centre of
//    frame i: pan = atan(tx / focal_i) (content moving right = view turning
//    left), tilt = atan(ty / focal_i) (content moving down = view turning up).
// Translation of the camera is not observable this way: it shows up as pan
// and tilt, which is what a 2-D stabiliser measures.
struct SimilarityCamera {
  double pan_deg = 0, tilt_deg = 0, roll_deg = 0;
  double focal_px = 0;
};
SimilarityCamera CameraFromSimilarity(const Eigen::Matrix3d& frame0_to_i, double width,
                                      double height, double focal0_px);

// Normalised interpolation between two keyframe cameras (slerp of the
// rotation, geometric mean of the focal), u in [0, 1].
CameraFrame InterpolateFrames(const CameraFrame& a, const CameraFrame& b, double u);

}  // namespace hapcine::bench
