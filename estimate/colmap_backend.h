#pragma once
// `--backend colmap`: the same question answered by COLMAP's incremental SfM,
// as a reference and a fallback. Frames are written (working resolution, JPEG)
// to a temporary folder, then
//   colmap feature_extractor  --ImageReader.single_camera 0 (one camera per frame,
//                             so zoom is free) --ImageReader.camera_model SIMPLE_PINHOLE
//                             --SiftExtraction.use_gpu 0
//   colmap sequential_matcher --SiftMatching.use_gpu 0
//   colmap mapper
//   colmap model_converter    --output_type TXT
// and the largest model is read with ReadColmapTextModel (datasets/colmap_text.h).
// COLMAP cannot initialise on pure rotation or a static camera: that, a
// missing binary or any failing step is a hapcine::Error naming the video.

#include <string>

#include "core/camera_path.h"
#include "estimate/camera_estimator.h"
#include "extract/frame_source.h"

namespace hapcine {

CameraPath EstimateWithColmap(FrameSource& source, const std::string& colmap_binary,
                              const ProgressFn& progress);

}  // namespace hapcine
