#pragma once
// Stills footage is split where a view links to nothing before it, but a
// split between stills is no picture cut: a later still may link by
// descriptors to an earlier shot's views (a ring of stills that came round
// to its start: FrameTracks::earlier_shot_links). Shots so linked are
// estimated as one: their frames are handed to the estimator one shot after
// the other in the order that puts the linked views next to each other, as
// one shot, and the path is put back in frame order afterwards.
//
// Video is not stills: a clip whose frames after the first are not all
// stills is passed on frame by frame, unchanged.

#include <deque>
#include <vector>

#include "core/camera_path.h"
#include "estimate/window/window_solver.h"
#include "extract/tracks.h"

namespace hapcine {

// The shots of `frames` (tracker order) in the order to estimate them:
// one list per group of shots linked across splits (a shot linked to none
// is a group of its own), groups by their first shot. In a group, each
// later shot goes before the shot its strongest link reaches when the link
// joins its last views to that shot's first ones (a ring come round), else
// after it.
std::vector<std::vector<int>> StillsShotGroups(const std::vector<FrameTracks>& frames);

class StillsRegrouper {
 public:
  // Frames in tracker order. Returns the frames ready for the estimator:
  // none while every frame after the first is a still (they are held);
  // the held ones and this one, in order, at the first that is not.
  std::vector<FrameTracks> Add(FrameTracks tracks);
  std::vector<FrameTracks> Add(std::vector<FrameTracks> frames);  // each in turn
  // The held stills: each group of linked shots one shot, the groups in
  // order, shots renumbered 0, 1, ... in that order.
  std::vector<FrameTracks> Finish();
  // Whether Finish() put frames out of order (a group of several shots).
  bool regrouped() const { return regrouped_; }
  // The estimate of what Finish() handed on: RestoreFrameOrder when
  // regrouped; returns `reports`, renumbered likewise.
  std::vector<WindowReport> Restore(CameraPath* path, std::vector<WindowReport> reports) const;

 private:
  std::vector<FrameTracks> held_;
  bool holding_ = true;
  bool regrouped_ = false;
};

// The estimated path back in frame order, shots numbered by first
// appearance (a group of linked stills shots keeps one number); the
// windows' reports (`reports`, may be null) take the same numbers.
void RestoreFrameOrder(CameraPath* path, std::vector<WindowReport>* reports = nullptr);

}  // namespace hapcine
