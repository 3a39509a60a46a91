#pragma once
// The lines `hapcine preview` burns into the top-left corner of each frame,
// so that a reviewer can name the moment and what drives the seat there:
//
//   00:01:02:12                  timecode HH:MM:SS:FF at the film's rate
//   shot 3  camera pan           the camera path's shot and per-frame model
//   effect traveling (crab_walk) the semantic effect (Table 1, its Table 2 metaphor)
//
// The effect comes from the track's `effect` column (a semantic track) or,
// for other tracks, from the classifier run on the camera path (what
// `hapcine haptics --effects-out` writes). A line whose source is missing is
// left out (no camera path: no camera model).

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "haptics/semantic_model.h"

namespace hapcine {

// Non-drop timecode of time t at the nominal rate round(fps) (24 for
// 23.976, as an editor counts frames): "01:02:03:04".
std::string Timecode(double t_s, double fps);

// A time given as seconds ("62.5") or a timecode ("00:01:02:12", frames at
// `fps`; "01:02.5" and "1:02:03.5" are minutes and hours with seconds).
// Throws UsageError naming `option` for anything else or a negative time.
double ParsePreviewTime(const std::string& text, double fps, const std::string& option);

class BurnInLabels {
 public:
  // `path` may be empty (no camera path); `effects` are used when the track
  // has no effect column.
  BurnInLabels(const CameraPath& path, const HapticTrack& track,
               std::vector<EffectSegment> effects);
  // The lines at film time t.
  std::vector<std::string> At(double t_s, double fps) const;

 private:
  const CameraFrame* FrameAt(double t_s) const;
  const HapticSample* SampleAt(double t_s) const;
  std::string EffectAt(double t_s) const;

  const CameraPath& path_;
  const HapticTrack& track_;
  std::vector<EffectSegment> effects_;
  bool track_has_effects_ = false;
};

// Draws `lines` top-left, white on a dark outline so they read on any
// picture; the size follows the frame's height (legible from 120 px up).
void DrawBurnIn(cv::Mat& bgr, const std::vector<std::string>& lines);

}  // namespace hapcine
