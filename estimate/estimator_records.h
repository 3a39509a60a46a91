#pragma once
// The estimator numbers frames by their position in what it was handed and
// shots as it met them. Those differ from the camera path's frames and shots
// with --skip-nonref (skipped frames are not handed on) and in stills
// footage whose linked shots are estimated together (stills_groups.h). This
// sink holds the estimator's records and, at the end, passes them on in the
// path's numbers, so that a report's windows name the frames they wrote.

#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/camera_path.h"
#include "core/diagnostics.h"

namespace hapcine {

class EstimatorRecords : public Diagnostics {
 public:
  explicit EstimatorRecords(Diagnostics* sink) : sink_(sink) {}
  bool Wants(const std::string& kind) const override { return hapcine::Wants(sink_, kind); }
  void Record(const std::string& kind, nlohmann::json fields) override;

  // Passes the held records on with every `frame`, `first_frame` and
  // `last_frame` (at any depth) mapped from a position to
  // frame_of_position[position], and every `shot` through shot_numbers
  // (a shot it does not list keeps its number). Later records pass at once.
  void Release(const std::vector<int>& frame_of_position, const std::map<int, int>& shot_numbers);

 private:
  Diagnostics* sink_;
  std::mutex mutex_;  // Record may be called from any thread
  bool holding_ = true;
  std::vector<std::pair<std::string, nlohmann::json>> held_;
};

// Each frame's shot in `path` (frames without one are left out).
std::map<int, int> ShotOfFrame(const CameraPath& path);

// How a renumbering moved the shots, from each frame's shot before and
// after it: old number -> new number.
std::map<int, int> ShotNumbers(const std::map<int, int>& shot_of_frame_before,
                               const std::map<int, int>& shot_of_frame_after);

}  // namespace hapcine
