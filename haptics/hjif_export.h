#pragma once
// Export of a haptic track to the MPEG-I Haptics interchange format
// (.hjif, ISO/IEC 23090-31, JSON, Main profile) so that the tracks can be
// used outside this project. See docs/haptics.md ("MPEG-I Haptics") for the
// mapping and for what the reference software (validate.sh) makes of it:
//   one perception per actuator (head, left hand, right hand), modality
//   "Position"; one channel per seat axis (its direction the axis, int8 with
//   the unit at 127); one Curve band per channel holding Basis effects of at
//   most 65535 ticks each (the binary format's 16-bit relative_position),
//   consecutive effects sharing their boundary keyframe; the keyframes are
//   the positions sampled at keyframe_rate_hz, amplitude_modulation =
//   position_mm / gain with gain = the workspace half range in mm
//   (perception_unit_exponent -3), so amplitudes lie in [-1, 1].

#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

struct HjifOptions {
  double keyframe_rate_hz = 100;  // keyframes per second per channel
  int timescale = 1000;           // ticks per second (positions are in ticks)
  double gain_m = 0.05;           // metres of amplitude 1.0 (workspace half range)
  std::string description;        // "" = the stem of the track's source; cut to 255 bytes
  std::string date;               // ISO 8601 date-time; "" = today, 00:00:00Z (or SOURCE_DATE_EPOCH's day)
  void Check() const;             // throws UsageError
};

// The binary format's limits (.hmpg, reference software IOBinaryFields.h).
constexpr long long kHjifMaxRelativePosition = 65535;     // 16 bits
constexpr long long kHjifMaxEffectPosition = (1LL << 25) - 1;  // 25 bits
constexpr size_t kHjifMaxDescriptionBytes = 255;           // 8-bit length
// body_part_mask bit of each actuator's body part (head, left hand, right hand).
uint32_t HjifBodyPartMask(Actuator a);

// `text` cut to at most `max_bytes` on a UTF-8 character boundary, control
// characters and bytes that are not UTF-8 replaced by '?'.
std::string HjifShortText(const std::string& text, size_t max_bytes);

// The whole document in memory (for tests and small tracks: a long film's
// keyframes take gigabytes as a json tree).
nlohmann::json HapticTrackToHjif(const HapticTrack& track, const HjifOptions& options);
// Writes the same text as HapticTrackToHjif(...).dump(1) + "\n", streaming
// the keyframes: memory does not grow with the track's length.
void WriteHjif(const HapticTrack& track, const HjifOptions& options, std::ostream& out);
// Atomic write (temporary file + rename).
void WriteHjifFile(const HapticTrack& track, const std::string& path, const HjifOptions& options);

}  // namespace hapcine
