#pragma once
// Reads an MPEG-I Haptics interchange file (.hjif, ISO/IEC 23090-31) as a
// haptic track, so that a track authored elsewhere in MPEG-I form plays on
// the HapSeat (`hapcine play --track film.hjif`, `eval --haptic-track`).
// What is read (docs/haptics.md, "MPEG-I Haptics"):
//   - Position perceptions only; amplitude x gain x 10^perception_unit_exponent
//     is metres (the perception's default exponent is 0);
//   - a channel's actuator from its body_part_target ("Head"; "Left" +
//     "Hand"; "Right" + "Hand") or else its body_part_mask (the bits
//     hapcine writes, HjifBodyPartMask); its seat axis from its direction,
//     which must lie along X, Y or Z (either sign);
//   - one Curve band per channel, curve_type Linear, Basis effects with
//     keyframes; effects in a band must not overlap (they may share a
//     boundary keyframe), and the curve is 0 outside its keyframes.
// Anything else throws hapcine::Error(file, one line naming what is
// unsupported, e.g. "perception 0 (Vibrotactile): only Position perceptions
// can play on the HapSeat").
// The file is parsed whole: about 2 GB for a two-hour film at 100 keyframes/s.

#include <nlohmann/json.hpp>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

// `source` names the file in errors; the track is sampled at rate_hz from
// the first keyframe to the last.
HapticTrack HjifToHapticTrack(const nlohmann::json& doc, const std::string& source,
                              double rate_hz = 1000);
HapticTrack ReadHjifFile(const std::string& path, double rate_hz = 1000);
// A .hjif (by extension, any case) through ReadHjifFile, anything else
// through ReadHapticTrackFile (*.haptic.csv).
HapticTrack ReadAnyHapticTrackFile(const std::string& path);
bool IsHjifPath(const std::string& path);

}  // namespace hapcine
