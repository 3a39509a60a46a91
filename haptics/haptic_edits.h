#pragma once
// A film's edits file, "<stem>.edits.json": what a haptic designer changed
// on top of the command-line settings (docs/formats.md, "Edits file").
//
//   {"format": "hapcine-edits", "version": 1, "revision": 3,
//    "shots": [{"shot": 0, "model": "semantic", "gain": 0.5, "mute": false,
//               "washout": {"mode": "adaptive", "return_accel_m_s2": 0.05}}],
//    "keyframes": [{"start_s": 1.0, "end_s": 2.5, "effect": "zoom_in",
//                   "intensity": 0.8}]}
//
// Per shot (the camera path's shot number): a model, a gain in [0, 4], a
// mute, washout settings; a field absent = the command line's setting.
// `keyframes`, when present, replaces the semantic model's classified effect
// segments for the whole film. MakeHapticTrack (haptic_models.h) applies the
// edits before the film-level safety, so no edit can leave the workspace.
// Unknown keys are errors (a typo must not be ignored), except "x-..." keys:
// those of the top level are kept (as JSON text) and written back, those
// inside a shot, its washout or a keyframe are accepted and dropped.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "haptics/haptic_model_kind.h"
#include "haptics/semantic_model.h"

namespace hapcine {

// Any subset of WashoutOptions (washout.h); unset = the command line's.
struct WashoutEdit {
  std::optional<std::string> mode;  // "adaptive", "highpass", "off"
  std::optional<double> return_accel_m_s2, window_s, tau_s;
  std::optional<int> order;
  bool operator==(const WashoutEdit& o) const;
};

struct ShotEdit {
  int shot = 0;  // the camera path's `shot` number
  std::optional<HapticModel> model;
  std::optional<double> gain;  // [0, 4], scales the shot's displacements
  std::optional<bool> mute;    // true = zero output, the same as gain 0
  std::optional<WashoutEdit> washout;
  // The factor on the shot's displacements: 0 when muted, else gain (or 1).
  double Scale() const { return mute.value_or(false) ? 0.0 : gain.value_or(1.0); }
  bool operator==(const ShotEdit& o) const;
};

constexpr double kMaxShotGain = 4.0;
constexpr size_t kMaxEditsFileBytes = 4 << 20;  // 4 MiB

struct HapticEdits {
  int64_t revision = 0;                                // the studio's stale check
  std::vector<ShotEdit> shots;                         // sorted by shot, unique
  std::optional<std::vector<EffectSegment>> keyframes;  // replaces the classifier's
  // Top-level "x-..." keys, name -> compact JSON text, written back as found.
  std::map<std::string, std::string> extensions;
  // No shot entry and no keyframes: the track is the command line's, byte for byte.
  bool empty() const { return shots.empty() && !keyframes; }
  const ShotEdit* FindShot(int shot) const;  // nullptr when not listed
  bool operator==(const HapticEdits& o) const;
};

// Throws hapcine::Error(source, reason) with a one-line reason naming the
// field ("shots[2].gain: must be in [0, 4]").
HapticEdits ParseHapticEdits(const std::string& json_text, const std::string& source);
// Pretty (2-space indent), keys in the documented order, ends with a newline.
std::string HapticEditsToJson(const HapticEdits& edits);
// Reads a regular file of at most kMaxEditsFileBytes; throws Error(path, reason).
HapticEdits ReadHapticEditsFile(const std::string& path);
// Writes atomically (AtomicFile): the old file stays whole until the rename.
void WriteHapticEditsFile(const HapticEdits& edits, const std::string& path);
// "<dir>/<stem>.edits.json" of a film ("a/film.mp4") or of its camera path
// ("a/film.camera.csv"): both give "a/film.edits.json".
std::string EditsPathForFilm(const std::string& film_or_camera_path);

}  // namespace hapcine
