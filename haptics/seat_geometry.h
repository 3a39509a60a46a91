#pragma once
// Geometry of the HapSeat (section 4.2 of the paper): where the three
// actuators sit around the user's body, how large their workspaces are, and
// the output rate. Seat frame: +X to the viewer's right, +Y up, +Z backward
// (the screen is at -Z), metres, origin anywhere (only differences are used).
//
// Defaults (built in, and documented in the configuration file
// haptics/hapseat.json; a JSON file may override any subset, docs/haptics.md):
//   G    = ( 0.00,  0.00,  0.00)  the user's chest, centre of the rotations
//   G_H  = ( 0.00,  0.45,  0.05)  head actuator: 45 cm above the chest, 5 cm behind
//   G_LA = (-0.25, -0.20, -0.25)  left-hand actuator on the left armrest
//   G_RA = ( 0.25, -0.20, -0.25)  right-hand actuator on the right armrest
// Each Novint Falcon has a ~0.10 m cube of workspace (half range 0.05 m);
// the models aim at +-usable_half_m and a final clamp at +-clamp_half_m
// catches anything that still gets through.

#include <Eigen/Core>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

struct SeatGeometry {
  // Centre of rotation G (the chest).
  Eigen::Vector3d center_m = Eigen::Vector3d(0.0, 0.0, 0.0);
  // Central positions of the actuators' workspaces, indexed by Actuator:
  // [0] head G_H, [1] left hand G_LA, [2] right hand G_RA.
  Eigen::Vector3d rest_m[kNumActuators] = {Eigen::Vector3d(0.0, 0.45, 0.05),
                                           Eigen::Vector3d(-0.25, -0.20, -0.25),
                                           Eigen::Vector3d(0.25, -0.20, -0.25)};
  // Edge of a workspace cube / 2 (a Falcon: 0.10 m cube).
  double workspace_half_m = 0.05;
  // What the models' scaling aims for on each axis (leaves a margin).
  double usable_half_m = 0.045;
  // Last line of defence: every output coordinate is clamped to +-this.
  double clamp_half_m = 0.048;
  // Stored rate of haptic tracks: the player interpolates them (monotone
  // cubic) to its 1 kHz loop within 0.1 mm (docs/haptics.md, "Stored rate").
  double rate_hz = 100;

  // Vector G -> G_A for actuator a.
  Eigen::Vector3d FromCenter(int a) const { return rest_m[a] - center_m; }
  // Throws UsageError unless 0 < usable <= clamp <= workspace_half, values
  // finite, rate in [10, 10000] Hz and no actuator sits at G.
  void Check() const;
};

// Reads a JSON file of overrides on top of the defaults. Keys (all optional):
//   "center_m": [x,y,z], "head_m": [x,y,z], "left_hand_m": [x,y,z],
//   "right_hand_m": [x,y,z], "workspace_half_m", "usable_half_m",
//   "clamp_half_m", "rate_hz". Unknown keys and wrong types are errors
// (Error "<file>: <reason>"), and the result must pass Check().
SeatGeometry LoadSeatGeometryFile(const std::string& path);
SeatGeometry ParseSeatGeometryJson(const std::string& text, const std::string& source_name);
// The full geometry as JSON text (what a --seat file may contain).
std::string SeatGeometryToJson(const SeatGeometry& seat);

}  // namespace hapcine
