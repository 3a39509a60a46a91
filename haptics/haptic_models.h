#pragma once
// Camera path in, haptic track out: the one entry point of the models.
//
//   MakeHapticTrack(path, options)
//     1. validates the path (camera_signals.h: absurd positions, gaps > 1 s
//        inside a shot),
//     2. samples the media clock of the path at rate_hz from its first to
//        its last frame,
//     3. runs the chosen model per shot: cinematic (Eq. 2-6 with washout
//        and scaling), semantic (Table 2 metaphors on hand-placed keyframes
//        or on automatically classified segments), random (0.5 Hz low-pass
//        noise), none (all zeros),
//     4. applies the film-level safety of washout.h: crossfades at cuts, a
//        per-sample step limit and a final clamp (counted in the metadata).
//
// Also here: the difference between two tracks (for `hapcine eval`) and a
// helper that makes two tracks with the same cinematic scaling.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "haptics/cinematic_model.h"
#include "haptics/effect_classifier.h"
#include "haptics/haptic_edits.h"
#include "haptics/haptic_model_kind.h"
#include "haptics/random_model.h"
#include "haptics/seat_geometry.h"
#include "haptics/semantic_model.h"
#include "haptics/washout.h"

namespace hapcine {

struct HapticOptions {
  HapticModel model = HapticModel::kCinematic;
  SeatGeometry seat;           // geometry, workspace, default rate
  double rate_hz = 0;          // output rate; 0 = seat.rate_hz (100 Hz)
  // Random model: the noise's seed; unset = DefaultRandomSeed(path), so each
  // film gets its own noise and the same film always the same.
  std::optional<uint64_t> seed;
  WashoutOptions washout;      // high-pass, cut ramps, speed limit
  CinematicOptions cinematic;  // reference depth, gain caps, scaling scope
  // Fixed cinematic factors (e.g. computed from another path); when unset
  // they are computed from this path (the paper's pre-processing pass).
  std::optional<CinematicScaling> cinematic_scaling;
  SemanticOptions semantic;       // pattern period, release
  ClassifierOptions classifier;   // automatic effect segments
  std::string keyframes_file;     // semantic: hand-placed effects; "" = classify
  // A designer's per-shot model, gain, mute and washout and keyframes
  // (haptic_edits.h), applied before the film-level safety; empty = none.
  HapticEdits edits;
  double random_cutoff_hz = 0.5;  // random: low-pass cutoff (the paper: 0.5 Hz)
  double max_gap_s = 1.0;         // reject time gaps longer than this inside a shot
  std::string source;             // written as the track's `source`; names errors
  double OutputRateHz() const { return rate_hz > 0 ? rate_hz : seat.rate_hz; }
  void Check() const;  // throws UsageError
};

HapticTrack MakeHapticTrack(const CameraPath& path, const HapticOptions& options);

// Throws Error(source, reason) for edits MakeHapticTrack would refuse on this
// path (a shot number the path does not have, a gain outside [0, 4], a
// washout setting out of range), so a save can be refused before it is written.
void CheckEditsForPath(const CameraPath& path, const HapticOptions& options);

// The semantic effect segments MakeHapticTrack uses for this path and these
// options: the edits' keyframes when present, else the keyframes file, else
// the classifier's segments.
std::vector<EffectSegment> EffectiveEffectSegments(const CameraPath& path,
                                                   const HapticOptions& options);

// A 64-bit FNV-1a hash of the path's frames (time, centre, rotation, field of
// view, shot): the random model's seed when none is given.
uint64_t DefaultRandomSeed(const CameraPath& path);

// Per actuator (indexed by Actuator) RMS and largest distance |a(t) - b(t)|
// in metres, over the samples of `a` inside the time range of `b` (b is
// interpolated). num_samples = 0 when the tracks do not overlap.
struct HapticDifference {
  double rms_m[kNumActuators] = {0, 0, 0};
  double max_m[kNumActuators] = {0, 0, 0};
  size_t num_samples = 0;
};
HapticDifference HapticTrackDifference(const HapticTrack& a, const HapticTrack& b);

// Tracks of `reference` and `other` made with the SAME cinematic scaling
// (computed from `reference`, unless options already fix it) and the same
// random seed (the reference's when unset), so that their
// difference measures the camera paths, not two different normalisations.
std::pair<HapticTrack, HapticTrack> MakeComparableHapticTracks(const CameraPath& reference,
                                                               const CameraPath& other,
                                                               HapticOptions options);

}  // namespace hapcine
