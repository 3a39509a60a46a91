#pragma once
// False cues: the body feels the opposite of what the eye sees. While a
// camera signal keeps its sign, the actuator component it drives should not
// move against it. The direction the eye sees is taken from the paper's
// Equations 2-6 with the per-shot scaling and no washout (the reference):
// for each actuator coordinate, the runs of frames over which the reference
// keeps moving the same way (faster than `still_fraction` of the shot's
// fastest reference coordinate) are the "camera keeps its sign" spans. In
// each run the counter-motion of a track is its largest retreat against that
// direction (the largest drawdown of sign * position), with its duration.
// Still moments (between runs) and the first `cut_ramp_s` after a cut are
// where a return is allowed, so they are not counted.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "haptics/cinematic_model.h"
#include "haptics/seat_geometry.h"

namespace hapcine {

struct FalseCueOptions {
  double still_fraction = 0.02;  // of the shot's peak reference speed
  double cut_ramp_s = 0.5;       // crossfade after a cut, not counted
};

struct ShotFalseCue {
  int shot = 0;                // `shot` column value
  double start_s = 0, end_s = 0;  // the shot's time span
  double counter_m = 0;        // largest counter-motion
  double duration_s = 0;       // how long that retreat lasted
  double at_s = 0;             // when it started
  int actuator = 0, axis = 0;  // where (Actuator, 0..2 = x, y, z)
  double peak_m = 0;           // largest |coordinate| of the track in the shot (after the crossfade)
};

// Per shot of `path`, the largest counter-motion of `track` (any actuator
// coordinate) against the reference made from `path` with `seat` and
// `cinematic`.
std::vector<ShotFalseCue> MeasureFalseCues(const CameraPath& path, const HapticTrack& track,
                                           const SeatGeometry& seat,
                                           const CinematicOptions& cinematic,
                                           const FalseCueOptions& options = {});

nlohmann::json FalseCuesToJson(const std::vector<ShotFalseCue>& cues);
std::string FormatFalseCueTable(const std::vector<ShotFalseCue>& cues);

}  // namespace hapcine
