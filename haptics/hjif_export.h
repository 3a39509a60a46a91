#pragma once
// Export of a haptic track to the MPEG-I Haptics interchange format
// (.hjif, ISO/IEC 23090-31, JSON, Main profile) so that the tracks can be
// used outside this project. See docs/haptics.md for the mapping:
//   one perception per actuator (head, left hand, right hand), modality
//   "Position"; one channel per axis (x, y, z); one Curve band per channel
//   holding one "Basis" effect whose keyframes are the positions sampled at
//   keyframe_rate_hz (relative_position in ticks of `timescale` from the
//   effect's position, amplitude_modulation = position_m / gain, with the
//   channel gain = the workspace half range, so amplitudes lie in [-1, 1]).
// Field names and types follow what the MPEG reference software's HJIF
// loader (MPEGGroup/HapticReferenceSoftware, IOJson::loadFile) requires;
// the test checks every one of them.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

struct HjifOptions {
  double keyframe_rate_hz = 100;  // keyframes per second per channel
  int timescale = 1000;           // ticks per second (positions are in ticks)
  double gain_m = 0.05;           // metres of amplitude 1.0 (workspace half range)
  std::string description;        // free text; default names the track's source/model
  std::string date;               // YYYY-MM-DD; "" = today (UTC)
  void Check() const;             // throws UsageError
};

// The whole document in memory (for tests and small tracks: a long film's
// keyframes take gigabytes as a json tree).
nlohmann::json HapticTrackToHjif(const HapticTrack& track, const HjifOptions& options);
// Writes the same text as HapticTrackToHjif(...).dump(1) + "\n", streaming
// the keyframes: memory does not grow with the track's length.
void WriteHjif(const HapticTrack& track, const HjifOptions& options, std::ostream& out);
// Atomic write (temporary file + rename).
void WriteHjifFile(const HapticTrack& track, const std::string& path, const HjifOptions& options);

}  // namespace hapcine
