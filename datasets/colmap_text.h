#pragma once
// Reads a COLMAP sparse model in text form (cameras.txt, images.txt,
// points3D.txt, as written by `colmap model_converter --output_type TXT`)
// and turns it into a camera path (docs/formats.md, "Camera path specification"):
//  - COLMAP stores cam_from_world with OpenCV camera axes (+Z forward,
//    +Y down); the file wants world_from_cam with OpenGL axes, so Y and Z
//    are flipped: R_gl = F R F, c_gl = F c, F = diag(1, -1, -1).
//  - The first registered frame is put at the origin with identity rotation.
//  - Positions are divided by the median depth of the 3-D points seen by that
//    first frame (1 unit = median scene depth); no points: left unscaled.
//  - The frame index is the last run of digits in the image name
//    (e.g. "frame_000123.jpg" -> 123).
//  - Focal length: the camera's first parameter (f or fx), rescaled from the
//    camera's width to `decoded_width` when that is given (> 0).

#include <string>
#include <vector>

#include "core/camera_path.h"

namespace hapcine {

struct ColmapReadOptions {
  // Presentation time of every decoded frame, by frame index. When given,
  // the path has one row per entry; frames COLMAP did not register are
  // `lost` (model kLostModel, confidence 0) with the previous registered
  // pose (or the next one at the start) as placeholder. When empty, only registered frames are written, with
  // time_s = frame / fps.
  std::vector<double> frame_times;
  double fps = 25;        // used only without frame_times
  int decoded_width = 0;  // rescale focal lengths to this width (0: the camera's width)
};

// Throws hapcine::Error("<dir>/<file>:<line>", reason) on unreadable or
// malformed files, or when no image is registered.
CameraPath ReadColmapTextModel(const std::string& dir, const ColmapReadOptions& options = {});

}  // namespace hapcine
