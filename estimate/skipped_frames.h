#pragma once
// Frames the decoder skipped (FrameSourceOptions::skip_nonref_frames) get
// a pose between their estimated neighbours, so the camera path still has
// every frame of the video.

#include <vector>

#include "core/camera_path.h"

namespace hapcine {

struct SkippedFrame {
  int index = 0;      // frame index in presentation order
  double time_s = 0;  // presentation time
};

// An interpolated frame's confidence, as a share of its neighbours' lower one:
// it was not tracked, only placed between two frames that were.
constexpr double kSkippedFrameConfidence = 0.8;

// Inserts one frame per `skipped` entry into `path` (sorted by frame index,
// as are both inputs). Between two estimated frames of the same shot, at
// its time's fraction u of the way: rotation slerp, centre linear, focal
// geometric (log-linear); model and shot of the later neighbour (the
// interval's motion). Otherwise (either neighbour lost, at either end, or
// across a shot boundary) the frame is lost (model kLostModel, confidence 0)
// with the nearest earlier frame's pose as placeholder, or the first later
// one's before any.
// Entries whose index the path already has are ignored. `width_px`: the
// decoded width (the frames' fov_deg and focal_px refer to it).
void InsertSkippedFrames(const std::vector<SkippedFrame>& skipped, int width_px, CameraPath* path);

}  // namespace hapcine
