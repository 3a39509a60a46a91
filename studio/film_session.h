#pragma once
// One film of the studio: its camera path, the haptic track rendered from it
// (MakeHapticTrack, the code of `hapcine haptics`, with the film's edits
// file), and both as level-of-detail curves (curves_lod.h). A save parses the
// edits, refuses a stale revision, re-renders the track and only then writes
// the edits file and swaps the new track in: readers never see a half state.
// Saves are serialised per film; reads take a snapshot and never wait for a
// render.

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera_path.h"
#include "core/haptic_track.h"
#include "estimate/shot_quality.h"
#include "haptics/haptic_models.h"
#include "studio/curves_lod.h"
#include "studio/media_tools.h"

namespace hapcine::studio {

// Requests the server answers with a 4xx: the status and a one-line message.
struct HttpError {
  int status = 400;
  std::string message;
  nlohmann::json extra = nlohmann::json::object();  // merged into the error body
};

struct ShotSpan {
  int shot = 0;
  double start_s = 0, end_s = 0;
};

class FilmSession {
 public:
  // `film`: the video; `camera_csv`: its camera path; `options`: the command
  // line's haptic settings. Reads the edits file beside the film
  // (EditsPathForFilm) when there is one and renders the track. Throws
  // hapcine::Error naming the file.
  FilmSession(std::string id, std::string film, std::string camera_csv, HapticOptions options);

  const std::string& id() const { return id_; }
  const std::string& film() const { return film_; }
  std::string name() const;  // the film's file name
  double duration_s() const { return duration_s_; }
  const MediaProbe& media() const { return media_; }
  const std::vector<ShotSpan>& shots() const { return shots_; }
  // "<folder>/<stem>.<suffix>" beside the film.
  std::string OutputPath(const std::string& suffix) const;
  // The folder for the proxy and thumbnails: <film folder>/.hapcine/studio/.
  std::string CacheDir() const;

  nlohmann::json Summary() const;  // GET /api/films entry
  nlohmann::json Details() const;  // GET /api/films/<id>
  std::string CurvesJson(double from_s, double to_s, int points) const;
  // The samples in [from_s, to_s], cut to 60 s; throws HttpError when to < from.
  nlohmann::json TrackJson(double from_s, double to_s) const;
  std::string EditsJson() const;
  int64_t revision() const;
  // PUT /api/films/<id>/edits: {"revision": new}; throws HttpError 400 (the
  // parser's or the render's one line), 409 (stale: body revision is not the
  // current one; {"revision": current} in the error body).
  nlohmann::json SaveEdits(const std::string& body);
  std::shared_ptr<const HapticTrack> track() const;
  const HapticOptions& options() const { return options_; }

 private:
  struct Rendered;
  std::shared_ptr<const Rendered> Snapshot() const;
  std::shared_ptr<const Rendered> Render(const HapticEdits& edits) const;

  std::string id_, film_, camera_csv_, edits_path_;
  HapticOptions options_;
  CameraPath path_;
  std::vector<ShotQuality> quality_;
  std::vector<ShotSpan> shots_;
  double duration_s_ = 0;
  MediaProbe media_;
  CurveGroup camera_curves_;
  mutable std::mutex mu_;   // guards rendered_
  std::mutex save_mu_;      // one save at a time
  std::shared_ptr<const Rendered> rendered_;
};

// The camera curves: pan, tilt, roll (degrees, relative to each shot's first
// frame), fov (degrees), tx, ty, tz (path units, in the shot's first camera
// frame), confidence (lost frames 0; frames without one 1).
CurveGroup CameraCurves(const CameraPath& path);
// The actuator curves, millimetres: head_x ... right_z.
CurveGroup TrackCurves(const HapticTrack& track);

}  // namespace hapcine::studio
