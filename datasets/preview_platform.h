#pragma once
// The motion platform in `hapcine preview --platform TRACK.platform.csv`: a
// drawn seat on its platform that moves with the track, so a person can
// judge the cueing without hardware. Three orthographic views of the same
// wireframe (seat pan, backrest, top plate, the fixed base and a jack), side
// by side: "behind" the seat (X right, Y up: heave, sway, roll), "side" from
// its right (screen to the left: heave, surge, pitch) and "top" (screen up:
// sway, surge, yaw). The home pose is drawn grey under the
// moving seat; the pose is printed under the views. Real size: a 0.1 m
// heave is a tenth of the seat's height.

#include <opencv2/core.hpp>

#include "platform/platform_track.h"

namespace hapcine {

// Draws the platform at time t (the track interpolated) into `r` of `img`,
// and, when `response` is given (platform/sim_platform.h), where a
// simulated platform is, in light blue.
void DrawPlatformInset(cv::Mat& img, const cv::Rect& r, const PlatformTrack& track, double t,
                       const PlatformTrack* response = nullptr);

// The track's pose at time t: linear interpolation, clamped to the ends.
PlatformPose PlatformPoseAt(const PlatformTrack& track, double t);

}  // namespace hapcine
