#pragma once
// Feature tracks, streamed frame by frame: what extract/ hands to estimate/.
// Coordinates are in pixels of the *decoded* frame (not the working image;
// for anamorphic video the display frame, resampled to square pixels),
// origin at the top-left pixel's centre... i.e. OpenCV's convention, so the
// estimator can use the decoded size's image centre as principal point
// ((width - 1) / 2, (height - 1) / 2). The tracker works on a downscaled image
// and maps back with p_decoded = (p_working + 0.5) / scale - 0.5 (per axis):
// pixel *edges* scale, pixel centres sit half a pixel inside them.
//
// Track ids are unique over the whole video and never reused. A track normally
// has one point per consecutive frame; a track re-linked by descriptor matching
// (FrameTracks::recovered) may skip the frames between its last good frame and
// the recovery frame. Every track ends at a shot boundary or blank frame,
// except where a still links to an earlier stills shot
// (FrameTracks::earlier_shot_links): that shot's tracks continue there.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace hapcine {

enum class ShotBoundary {
  kNone = 0,  // same shot as the previous frame
  kCut,       // hard cut before this frame
  kFade,      // gradual transition (fade/dissolve) ended before this frame
  kStart,     // first frame of the video
};

struct TrackPoint {
  long track_id = 0;   // unique over the whole video
  Eigen::Vector2d px;  // position in decoded-frame pixels
};

struct FrameTracks {
  int index = 0;      // decoded frame index
  double time_s = 0;  // presentation time
  // Frames of the video from the previous FrameTracks to this one (the
  // index gap FeatureTracker saw): 1, or more where the decoder skipped
  // frames (--skip-nonref). The estimator counts its keyframe gap, window
  // length and smoothing in these.
  int step = 1;
  int shot = 0;       // 0-based shot index
  ShotBoundary boundary = ShotBoundary::kNone;
  bool blank = false;  // black/blank/mid-fade frame: flagged, not tracked
  // Tracking health in [0, 1]: fraction of the wanted tracks alive and
  // verified (forward-backward). Low on blur, low texture, fades.
  // Exactly: (KLT survivors + re-linked tracks) / max_tracks, capped at 1; on
  // a shot's first tracked frame the fresh detections / max_tracks; at most
  // 0.25 when `transition`; 0 when `blank`.
  double quality = 0;
  bool recovered = false;  // tracks were re-linked by descriptor matching
  // Linked by descriptors across a motion beyond KLT's reach (median motion
  // of a KLT window or more): the camera jumped, the path is not continuous
  // from the previous frame to this one (the estimator does not smooth across).
  bool jump = false;
  // Inside a suspected gradual transition (fade/dissolve in progress): the
  // tracks are kept but quality is capped (see docs/extract.md).
  bool transition = false;
  // Linked as a still (an image folder, --stills, or a video found to be a
  // sequence of stills): its pose is not smoothed with its neighbours'.
  bool still = false;
  // Stills: views of earlier shots of the same stills this still links to
  // by descriptors (verified as any link is), whose tracks it continues
  // (those track ids reappear here). In stills footage a split is no
  // picture cut: a ring that came round links its last views to its first.
  struct ShotLink {
    int shot = 0;   // the earlier shot
    int frame = 0;  // the view of it linked to (FrameTracks::index)
    int verified = 0;  // verified descriptor matches
  };
  std::vector<ShotLink> earlier_shot_links;
  // Stills: linked to the view before by fewer than twice the verified
  // matches a link needs (the tracker's "well linked"): a weak first
  // interval for a chain to start from.
  bool weak_link = false;
  // Tracking broke inside the shot at or before this frame (KLT, the ORB
  // re-links and the SIFT probe all lost the last frame: blur, a flash, an
  // occluder) and the tracker is still trying to link a later frame back to
  // the last frame before the break by descriptors. The estimator holds its
  // split decision until a frame without it: one that continues the tracks
  // of the frame before the break (the break's frames are lost, the shot
  // goes on) or not (the shot is split where it broke, as without the link).
  bool bridging = false;
  std::vector<TrackPoint> points;  // tracks alive in this frame
};

}  // namespace hapcine
