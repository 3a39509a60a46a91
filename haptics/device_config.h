#pragma once
// Which Falcon is which actuator: a small JSON file mapping FTDI serial
// numbers to seat roles, with per-device mounting and force limit.
//
//   {
//     "devices": [
//       {"role": "head",  "serial": "FTB1C2D3", "mount": "behind", "max_force_n": 5},
//       {"role": "left",  "serial": "FTA1B2C3"},
//       {"role": "right", "serial": "FTA9B8C7", "mount": "front"}
//     ]
//   }
//
// role: head | left | right (each at most once; missing roles are absent).
// mount: how the Falcon faces the seat. "front" (default): the device stands
//   in front of the user and faces them, its +z (out of the device) is the
//   seat's +Z (backward), so seat_from_falcon = identity. "behind": it stands
//   behind the user facing forward (rotation of 180 deg about Y).
//   Or give "seat_from_falcon": [[...],[...],[...]] (a rotation, rows).
// max_force_n: optional limit below the device's 9 N.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

struct SeatDeviceConfig {
  std::string serial;
  Eigen::Matrix3d seat_from_falcon = Eigen::Matrix3d::Identity();
  std::optional<double> max_force_n;
};

struct SeatConfig {
  std::array<std::optional<SeatDeviceConfig>, kNumActuators> roles;  // by Actuator
};

// Throws hapcine::Error("<path>", reason) on any malformed entry.
SeatConfig ParseSeatConfig(const std::string& json_text, const std::string& source_name);
SeatConfig ReadSeatConfigFile(const std::string& path);

}  // namespace hapcine
