#include "studio/film_session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/rotation.h"
#include "haptics/camera_signals.h"
#include "haptics/effect_classifier.h"
#include "haptics/keyframes.h"
#include "haptics/seat_geometry.h"

namespace hapcine::studio {
namespace fs = std::filesystem;

struct FilmSession::Rendered {
  HapticEdits edits;
  std::shared_ptr<const HapticTrack> track;
  CurveGroup curves;  // the track's, millimetres
  std::vector<EffectSegment> effects;
};

namespace {

constexpr double kMaxTrackRangeS = 60.0;

// Start and end of each shot: a shot ends where the next begins; the last
// one frame period after its last frame.
std::vector<ShotSpan> ShotSpans(const CameraPath& path) {
  std::vector<ShotSpan> spans;
  const std::vector<ShotRange> ranges = SplitShots(path);
  const double fps = path.fps();
  for (size_t i = 0; i < ranges.size(); ++i) {
    ShotSpan s;
    s.shot = ranges[i].shot;
    s.start_s = path.frames[ranges[i].first].time_s;
    s.end_s = i + 1 < ranges.size() ? path.frames[ranges[i + 1].first].time_s
                                    : path.frames[ranges[i].last].time_s + (fps > 0 ? 1.0 / fps : 0.0);
    spans.push_back(s);
  }
  return spans;
}

nlohmann::json QualityJson(const ShotQuality* q) {
  if (!q) return nullptr;
  auto optional = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"median_confidence", q->median_confidence},
          {"inlier_ratio", optional(q->inlier_ratio)},
          {"reprojection_rms_px", optional(q->rms_px)},
          {"focal_observable", optional(q->focal_observable)},
          {"lost_frames", q->lost},
          {"doubtful", q->doubtful}};
}

// The command line's washout with a shot's edits on top.
nlohmann::json WashoutJson(const WashoutOptions& w, const ShotEdit* edit) {
  nlohmann::json j = {{"mode", WashoutModeName(w.mode)},
                      {"return_accel_m_s2", w.return_accel_m_s2},
                      {"window_s", w.window_s},
                      {"tau_s", w.tau_s},
                      {"order", w.order}};
  if (!edit || !edit->washout) return j;
  const WashoutEdit& e = *edit->washout;
  if (e.mode) j["mode"] = *e.mode;
  if (e.return_accel_m_s2) j["return_accel_m_s2"] = *e.return_accel_m_s2;
  if (e.window_s) j["window_s"] = *e.window_s;
  if (e.tau_s) j["tau_s"] = *e.tau_s;
  if (e.order) j["order"] = *e.order;
  return j;
}

nlohmann::json EffectsJson(const std::vector<EffectSegment>& effects) {
  nlohmann::json out = nlohmann::json::array();
  for (const EffectSegment& e : effects) {
    out.push_back({{"start_s", e.start_s},
                   {"end_s", e.end_s},
                   {"effect", EffectName(e.effect)},
                   {"intensity", e.intensity}});
  }
  return out;
}

void AddSeries(CurveGroup* g, const std::string& name, std::vector<float> values) {
  g->names.push_back(name);
  g->series.emplace_back(std::move(values));
}

}  // namespace

CurveGroup CameraCurves(const CameraPath& path) {
  const size_t n = path.frames.size();
  std::vector<float> pan(n), tilt(n), roll(n), fov(n), tx(n), ty(n), tz(n), confidence(n);
  CurveGroup g;
  g.time_s.resize(n);
  for (const ShotRange& shot : SplitShots(path)) {
    const Eigen::Quaterniond first_inv =
        Eigen::Quaterniond(path.frames[shot.first].world_from_cam).conjugate();
    const Eigen::Vector3d first_centre = path.frames[shot.first].center;
    for (size_t i = shot.first; i <= shot.last; ++i) {
      const CameraFrame& f = path.frames[i];
      const PanTiltRoll a = PanTiltRollFromQuaternion(first_inv * Eigen::Quaterniond(f.world_from_cam));
      const Eigen::Vector3d c = first_inv * (f.center - first_centre);
      g.time_s[i] = f.time_s;
      pan[i] = static_cast<float>(a.pan_deg);
      tilt[i] = static_cast<float>(a.tilt_deg);
      roll[i] = static_cast<float>(a.roll_deg);
      fov[i] = static_cast<float>(f.fov_deg);
      tx[i] = static_cast<float>(c.x());
      ty[i] = static_cast<float>(c.y());
      tz[i] = static_cast<float>(c.z());
      confidence[i] = IsLost(f) ? 0.0f : static_cast<float>(f.confidence ? *f.confidence : 1.0);
    }
  }
  AddSeries(&g, "pan", std::move(pan));
  AddSeries(&g, "tilt", std::move(tilt));
  AddSeries(&g, "roll", std::move(roll));
  AddSeries(&g, "fov", std::move(fov));
  AddSeries(&g, "tx", std::move(tx));
  AddSeries(&g, "ty", std::move(ty));
  AddSeries(&g, "tz", std::move(tz));
  AddSeries(&g, "confidence", std::move(confidence));
  return g;
}

CurveGroup TrackCurves(const HapticTrack& track) {
  CurveGroup g;
  const size_t n = track.samples.size();
  g.time_s.resize(n);
  for (size_t i = 0; i < n; ++i) g.time_s[i] = track.samples[i].time_s;
  for (int a = 0; a < kNumActuators; ++a) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<float> mm(n);
      for (size_t i = 0; i < n; ++i) mm[i] = static_cast<float>(track.samples[i].pos_m[a][axis] * 1000.0);
      const std::string actuator = a == 0 ? "head" : a == 1 ? "left" : "right";
      AddSeries(&g, actuator + "_" + "xyz"[axis], std::move(mm));
    }
  }
  return g;
}

FilmSession::FilmSession(std::string id, std::string film, std::string camera_csv,
                         HapticOptions options)
    : id_(std::move(id)), film_(std::move(film)), camera_csv_(std::move(camera_csv)),
      options_(std::move(options)) {
  path_ = ReadCameraPathFile(camera_csv_);
  if (path_.frames.empty()) throw Error(camera_csv_, "the camera path has no frames");
  const std::vector<int> lines = CsvDataRowLines(camera_csv_);
  ValidatePathForHaptics(path_, camera_csv_, options_.max_gap_s, &lines);
  if (options_.source.empty()) options_.source = film_;
  quality_ = ReadShotQuality(path_);
  shots_ = ShotSpans(path_);
  duration_s_ = shots_.empty() ? 0.0 : shots_.back().end_s;
  media_ = ProbeMedia(film_);
  camera_curves_ = CameraCurves(path_);
  edits_path_ = EditsPathForFilm(film_);
  std::error_code ec;
  rendered_ = Render(fs::exists(edits_path_, ec) ? ReadHapticEditsFile(edits_path_) : HapticEdits{});
}

std::shared_ptr<const FilmSession::Rendered> FilmSession::Render(const HapticEdits& edits) const {
  auto r = std::make_shared<Rendered>();
  r->edits = edits;
  HapticOptions options = options_;
  options.edits = edits;
  r->track = std::make_shared<const HapticTrack>(MakeHapticTrack(path_, options));
  r->curves = TrackCurves(*r->track);
  r->effects = EffectiveEffectSegments(path_, options);
  return r;
}

std::shared_ptr<const FilmSession::Rendered> FilmSession::Snapshot() const {
  std::lock_guard<std::mutex> lock(mu_);
  return rendered_;
}

std::string FilmSession::name() const { return fs::path(film_).filename().string(); }

std::string FilmSession::OutputPath(const std::string& suffix) const {
  const fs::path p(film_);
  return (p.parent_path() / (p.stem().string() + "." + suffix)).string();
}

std::string FilmSession::CacheDir() const {
  return (fs::path(film_).parent_path() / ".hapcine" / "studio").string();
}

nlohmann::json FilmSession::Summary() const {
  return {{"id", id_},
          {"name", name()},
          {"duration_s", duration_s_},
          {"fps", path_.fps()},
          {"width", path_.width()},
          {"height", path_.height()},
          {"shots", shots_.size()},
          {"model", HapticModelName(options_.model)}};
}

nlohmann::json FilmSession::Details() const {
  const auto r = Snapshot();
  nlohmann::json j = Summary();
  j["revision"] = r->edits.revision;
  const std::string base = "/api/films/" + id_;
  j["video_url"] = base + (media_.browser_playable ? "/video" : "/proxy.mp4");
  nlohmann::json shots = nlohmann::json::array();
  for (const ShotSpan& s : shots_) {
    const ShotQuality* q = nullptr;
    for (const ShotQuality& candidate : quality_) {
      if (candidate.shot == s.shot) q = &candidate;
    }
    const ShotEdit* edit = r->edits.FindShot(s.shot);
    shots.push_back({{"shot", s.shot},
                     {"start_s", s.start_s},
                     {"end_s", s.end_s},
                     {"model", HapticModelName(edit && edit->model ? *edit->model : options_.model)},
                     {"gain", edit && edit->gain ? *edit->gain : 1.0},
                     {"mute", edit && edit->mute ? *edit->mute : false},
                     {"washout", WashoutJson(options_.washout, edit)},
                     {"quality", QualityJson(q)},
                     {"thumbnail_url", base + "/thumbnails/" + std::to_string(s.shot) + ".jpg"}});
  }
  j["shots"] = shots;
  j["effects"] = EffectsJson(r->effects);
  j["seat"] = nlohmann::json::parse(SeatGeometryToJson(options_.seat));
  return j;
}

std::string FilmSession::CurvesJson(double from_s, double to_s, int points) const {
  const auto r = Snapshot();
  return CurveBucketsToJson(QueryCurves({&camera_curves_, &r->curves}, from_s, to_s, points));
}

nlohmann::json FilmSession::TrackJson(double from_s, double to_s) const {
  if (to_s < from_s) throw HttpError{400, "to must not be before from"};
  to_s = std::min(to_s, from_s + kMaxTrackRangeS);  // at most 60 s per answer
  const auto r = Snapshot();
  const std::vector<HapticSample>& samples = r->track->samples;
  auto first = std::lower_bound(samples.begin(), samples.end(), from_s,
                                [](const HapticSample& s, double t) { return s.time_s < t; });
  nlohmann::json t = nlohmann::json::array(), head = t, left = t, right = t;
  nlohmann::json* columns[kNumActuators] = {&head, &left, &right};
  for (auto it = first; it != samples.end() && it->time_s <= to_s; ++it) {
    t.push_back(it->time_s);
    for (int a = 0; a < kNumActuators; ++a) {
      const Eigen::Vector3d mm = it->pos_m[a] * 1000.0;
      columns[a]->push_back({mm.x(), mm.y(), mm.z()});
    }
  }
  return {{"rate_hz", r->track->rate_hz}, {"t", t}, {"head", head}, {"left", left}, {"right", right}};
}

std::string FilmSession::EditsJson() const { return HapticEditsToJson(Snapshot()->edits); }

int64_t FilmSession::revision() const { return Snapshot()->edits.revision; }

std::shared_ptr<const HapticTrack> FilmSession::track() const { return Snapshot()->track; }

nlohmann::json FilmSession::SaveEdits(const std::string& body) {
  HapticEdits edits;
  try {
    edits = ParseHapticEdits(body, "edits");
    HapticOptions options = options_;
    options.edits = edits;
    CheckEditsForPath(path_, options);  // a shot the path lacks, a value out of range
  } catch (const Error& e) {
    throw HttpError{400, e.what()};
  }
  // One save at a time: the revision check, the render and the write are
  // one step, so of two saves based on the same revision exactly one wins.
  std::lock_guard<std::mutex> saving(save_mu_);
  const int64_t current = revision();
  if (edits.revision != current)
    throw HttpError{409,
                    "stale edits: based on revision " + std::to_string(edits.revision) +
                        ", the film is at revision " + std::to_string(current) +
                        " (saved from another tab?): reload",
                    {{"revision", current}}};
  edits.revision = current + 1;
  std::shared_ptr<const Rendered> rendered;
  try {
    rendered = Render(edits);
  } catch (const Error& e) {
    throw HttpError{400, e.what()};
  }
  WriteHapticEditsFile(edits, edits_path_);
  {
    std::lock_guard<std::mutex> lock(mu_);
    rendered_ = rendered;
  }
  return {{"revision", edits.revision}};
}

}  // namespace hapcine::studio
