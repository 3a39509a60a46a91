#include "haptics/haptic_models.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/csv.h"
#include "core/error.h"
#include "haptics/camera_signals.h"
#include "haptics/confidence.h"
#include "haptics/keyframes.h"

namespace hapcine {
namespace {

// Per-frame values of the cinematic model resampled at the samples' times
// (already set): linear inside a shot, held from a shot's last frame until the next cut.
void ResampleFrames(const CameraPath& path, const std::vector<ShotRange>& shots,
                    const std::vector<ActuatorFrame>& per_frame,
                    std::vector<HapticSample>* samples) {
  size_t k = 0;  // current shot
  size_t i = 0;  // current frame
  for (HapticSample& out : *samples) {
    const double t = out.time_s;
    while (k + 1 < shots.size() && path.frames[shots[k + 1].first].time_s <= t) ++k;
    const ShotRange& s = shots[k];
    i = std::max(i, s.first);
    while (i + 1 <= s.last && path.frames[i + 1].time_s <= t) ++i;
    if (i >= s.last || t <= path.frames[i].time_s) {
      std::copy(per_frame[i].begin(), per_frame[i].end(), out.pos_m);
    } else {
      const double ta = path.frames[i].time_s, tb = path.frames[i + 1].time_s;
      const double w = (t - ta) / (tb - ta);
      for (int a = 0; a < kNumActuators; ++a) {
        out.pos_m[a] = (1 - w) * per_frame[i][a] + w * per_frame[i + 1][a];
      }
    }
  }
}

void CopyPositions(const std::vector<ActuatorFrame>& frames, std::vector<HapticSample>* samples) {
  for (size_t i = 0; i < frames.size(); ++i) {
    std::copy(frames[i].begin(), frames[i].end(), (*samples)[i].pos_m);
  }
}

// The `shot` of each sample (when the path has one) and its `effect` (semantic).
void LabelSamples(const CameraPath& path, const std::vector<ShotRange>& shots,
                  const std::vector<CameraEffect>& effects, std::vector<HapticSample>* samples) {
  const bool has_shot_column = std::any_of(path.frames.begin(), path.frames.end(),
                                           [](const CameraFrame& f) { return f.shot.has_value(); });
  size_t k = 0;
  std::optional<CameraEffect> last_effect;
  OptionalName last_name;
  for (size_t i = 0; i < samples->size(); ++i) {
    HapticSample& s = (*samples)[i];
    if (has_shot_column) {
      while (k + 1 < shots.size() && path.frames[shots[k + 1].first].time_s <= s.time_s) ++k;
      s.shot = shots[k].shot;
    }
    if (effects.empty()) continue;
    if (effects[i] != last_effect) last_name = EffectName(effects[i]);
    last_effect = effects[i];
    s.effect = last_name;
  }
}

// A media clock this far from zero cannot be sampled at a haptic rate in
// double precision (at 1e15 s neighbouring doubles are 0.125 s apart), nor
// written with the track's six decimals; 1e8 s is over three years.
constexpr double kMaxMediaClockS = 1e8;

// Output sample times at `rate` from the path's first frame up to its last
// one, and past it when it falls between two samples: a player interpolating
// a 100 Hz track must reach the last frame's pose, not hold the sample up to
// 10 ms before it. Throws Error(source) if neighbouring times cannot be told apart.
std::vector<double> SampleTimes(const CameraPath& path, double rate, const std::string& source) {
  const double t0 = path.frames.front().time_s;
  const double t1 = path.frames.back().time_s;
  const size_t n = static_cast<size_t>(std::ceil((t1 - t0) * rate - 1e-6)) + 1;
  std::vector<double> time_s(n);
  for (size_t i = 0; i < n; ++i) {
    time_s[i] = t0 + static_cast<double>(i) / rate;
    if (i > 0 && !(time_s[i] > time_s[i - 1])) {
      throw Error(source, "time_s " + FormatDouble(time_s[i]) + " is too large to sample at " +
                              FormatDouble(rate) + " Hz");
    }
  }
  return time_s;
}

// The rate the player's loop runs at: a semantic track stored below it gets
// this rate's rows wherever its stored rows cannot follow it (below).
constexpr double kDenseRateHz = 1000;
// A kink: the velocity changes by K at one instant, and the monotone cubic
// rounds it off by about K * h / 8 (h: the row spacing). A smooth pattern's
// velocity changes by about the same from one row to the next (its
// acceleration times h), a kink's by K at one or two rows and not at their
// neighbours; a change of those changes above kKinkSpeedMS / 2 finds every
// kink of K > kKinkSpeedMS. 0.02 m/s: 0.025 mm at 100 Hz, a quarter of the
// 0.1 mm the stored rate may cost; the patterns' jerk (a dutch angle of
// 0.045 m at 0.7 s cycles: 0.003 m/s per row) stays far under it.
constexpr double kKinkSpeedMS = 0.02;

// The intervals (rows i to i+1) that stored rows cannot follow, each with
// its neighbours: around a kink (a pattern starting or stopping while it
// moves, a fast release), and where the speed limit acts or may act at
// 1 kHz, since its ramp starts at the first row that exceeds the limit and
// runs from there. Away from kinks the velocity inside an interval is within
// kKinkSpeedMS of its secant, so a secant that slow under the limit cannot reach it.
std::vector<char> DenseIntervals(const std::vector<HapticSample>& s,
                                 const std::vector<char>& limited_rows, double max_speed_m_s) {
  const size_t n = s.size();
  std::vector<char> dense(n > 1 ? n - 1 : 0, 0);
  auto mark = [&](size_t first, size_t last) {
    for (size_t j = first; j <= last && j < dense.size(); ++j) dense[j] = 1;
  };
  Eigen::Vector3d v_before[kNumActuators], dv_before[kNumActuators];
  for (size_t i = 0; i + 1 < n; ++i) {
    const double h = s[i + 1].time_s - s[i].time_s;
    bool fast = limited_rows[i + 1] != 0;
    for (int a = 0; a < kNumActuators; ++a) {
      const Eigen::Vector3d v = (s[i + 1].pos_m[a] - s[i].pos_m[a]) / h;
      fast |= v.cwiseAbs().maxCoeff() > max_speed_m_s - kKinkSpeedMS;
      const Eigen::Vector3d dv = i > 0 ? Eigen::Vector3d(v - v_before[a]) : Eigen::Vector3d::Zero();
      if (i > 1 && (dv - dv_before[a]).cwiseAbs().maxCoeff() > kKinkSpeedMS / 2)
        mark(i - 2, i);  // the intervals around rows i - 1 and i
      v_before[a] = v;
      dv_before[a] = dv;
    }
    if (fast) mark(i > 0 ? i - 1 : 0, i + 1);
  }
  return dense;
}

// time_s with the kDenseRateHz rows (on the grid from time_s's first row,
// the rows a 1 kHz track has) inside each dense interval.
std::vector<double> AddDenseRows(const std::vector<double>& time_s,
                                 const std::vector<char>& dense) {
  const double t0 = time_s.front();
  std::vector<double> out;
  out.reserve(time_s.size());
  for (size_t i = 0; i < time_s.size(); ++i) {
    out.push_back(time_s[i]);
    if (i >= dense.size() || !dense[i]) continue;
    const long first = static_cast<long>(std::floor((time_s[i] - t0) * kDenseRateHz + 1e-6)) + 1;
    const long last = static_cast<long>(std::ceil((time_s[i + 1] - t0) * kDenseRateHz - 1e-6)) - 1;
    for (long j = first; j <= last; ++j) out.push_back(t0 + static_cast<double>(j) / kDenseRateHz);
  }
  return out;
}

// The semantic track's rows below kDenseRateHz: the stored rate's, plus the
// 1 kHz rows of every interval they cannot follow, found on the track as
// made (cut crossfades and speed limit included) and again after adding
// rows until none are added. Inside those intervals the track is the 1 kHz
// track row for row; elsewhere it is smooth enough for the player's cubic.
std::vector<double> SemanticSampleTimes(std::vector<double> time_s,
                                        const std::vector<EffectSegment>& segs,
                                        const std::vector<double>& cut_times,
                                        const HapticOptions& o) {
  if (o.OutputRateHz() >= kDenseRateHz || time_s.size() < 2) return time_s;
  for (int pass = 0; pass < 4; ++pass) {
    std::vector<HapticSample> s(time_s.size());
    for (size_t i = 0; i < s.size(); ++i) s[i].time_s = time_s[i];
    CopyPositions(SemanticFrames(time_s, segs, o.seat, o.semantic), &s);
    ApplyCutTransitions(time_s, cut_times, o.washout.cut_ramp_s, &s);
    std::vector<char> limited_rows;
    LimitSpeed(o.washout.max_speed_m_s, o.OutputRateHz(), &s, &limited_rows);
    std::vector<double> refined =
        AddDenseRows(time_s, DenseIntervals(s, limited_rows, o.washout.max_speed_m_s));
    if (refined.size() == time_s.size()) break;
    time_s = std::move(refined);
  }
  return time_s;
}

std::vector<double> CutTimes(const CameraPath& path, const std::vector<ShotRange>& shots) {
  std::vector<double> cut_times;
  for (size_t k = 1; k < shots.size(); ++k) cut_times.push_back(path.frames[shots[k].first].time_s);
  return cut_times;
}

std::string JoinScales(const CinematicScaling& s, bool rotation) {
  std::ostringstream out;
  for (size_t i = 0; i < s.per_shot.size(); ++i) {
    if (i) out << ";";
    out << FormatDouble(rotation ? s.per_shot[i].mx : s.per_shot[i].kx);
  }
  return out.str();
}

// Per shot, the adaptive washout's return time constant (0 = none).
std::string JoinReturnTaus(const CinematicScaling& s) {
  std::ostringstream out;
  for (size_t i = 0; i < s.per_shot.size(); ++i) {
    out << (i ? ";" : "") << FormatDouble(s.per_shot[i].return_tau_s);
  }
  return out.str();
}

// The cinematic model's samples (Equations 2-6, scaling, washout) and its
// metadata: the factors, return time constants and reference depths per shot.
void MakeCinematicSamples(const CameraPath& path, const std::vector<ShotRange>& shots,
                          const HapticOptions& o, HapticTrack* track) {
  const CinematicScaling scaling =
      o.cinematic_scaling ? *o.cinematic_scaling
                          : ComputeCinematicScaling(path, o.seat, o.cinematic, o.washout);
  const auto per_frame = CinematicFrames(path, o.seat, o.cinematic, o.washout, scaling);
  ResampleFrames(path, shots, per_frame, &track->samples);
  track->metadata["cinematic_k_m_per_unit"] = JoinScales(scaling, false);
  track->metadata["cinematic_m"] = JoinScales(scaling, true);
  if (o.washout.mode == WashoutMode::kAdaptive) {
    track->metadata["return_tau_s"] = JoinReturnTaus(scaling);
    track->metadata["return_accel_m_s2"] = FormatDouble(o.washout.return_accel_m_s2);
  }
  std::string depths;
  for (const ShotRange& r : shots) {
    depths += (depths.empty() ? "" : ";") +
              FormatDouble(ShotReferenceDepth(path, r, o.cinematic.reference_depth_u));
  }
  track->metadata["reference_depth"] = depths;
  std::string gains;
  for (const double gain : ShotQualityGains(path, shots)) {
    gains += (gains.empty() ? "" : ";") + FormatDouble(gain);
  }
  track->metadata["confidence_gain"] = gains;
}

// The semantic segments of a path already joined across lost frames.
std::vector<EffectSegment> EffectSegmentsOfJoinedPath(const CameraPath& path,
                                                      const HapticOptions& o) {
  if (o.edits.keyframes) return *o.edits.keyframes;
  if (!o.keyframes_file.empty()) return ReadKeyframesFile(o.keyframes_file);
  return ClassifyEffects(path, o.classifier);
}

std::string EffectsFrom(const HapticOptions& o) {
  if (o.edits.keyframes) return "edits";
  return o.keyframes_file.empty() ? "classifier" : o.keyframes_file;
}

uint64_t RandomSeed(const CameraPath& read_path, const HapticOptions& o) {
  return o.seed ? *o.seed : DefaultRandomSeed(read_path);
}

// Whether the film's model, or an edit of one of its shots, is semantic.
bool UsesSemantic(const HapticOptions& o) {
  if (o.model == HapticModel::kSemantic) return true;
  return std::any_of(o.edits.shots.begin(), o.edits.shots.end(),
                     [](const ShotEdit& e) { return e.model == HapticModel::kSemantic; });
}

// The semantic model's effects (the edits', the keyframes file's, else the
// classifier's) when any shot uses it; none otherwise.
std::vector<EffectSegment> SemanticSegments(const CameraPath& path, const HapticOptions& o) {
  if (!UsesSemantic(o)) return {};
  return EffectSegmentsOfJoinedPath(path, o);
}

// The film's model over the whole path: positions into track->samples
// (their times already set), its metadata, and the semantic effect per sample.
void RunFilmModel(const CameraPath& path, const CameraPath& read_path,
                  const std::vector<ShotRange>& shots, const std::vector<double>& time_s,
                  const std::vector<EffectSegment>& segs, const HapticOptions& o,
                  HapticTrack* track, std::vector<CameraEffect>* effects) {
  switch (o.model) {
    case HapticModel::kNone:
      break;  // samples start centred
    case HapticModel::kCinematic:
      MakeCinematicSamples(path, shots, o, track);
      break;
    case HapticModel::kSemantic: {
      CopyPositions(SemanticFrames(time_s, segs, o.seat, o.semantic, effects), &track->samples);
      track->metadata["effects_from"] = EffectsFrom(o);
      track->metadata["effect_segments"] = std::to_string(segs.size());
      break;
    }
    case HapticModel::kRandom: {
      RandomOptions r;
      r.seed = RandomSeed(read_path, o);
      r.cutoff_hz = o.random_cutoff_hz;
      CopyPositions(RandomFrames(time_s.size(), o.OutputRateHz(), o.seat, r), &track->samples);
      track->metadata["seed"] = std::to_string(r.seed);
      track->metadata["seed_from"] = o.seed ? "option" : "content";
      track->metadata["cutoff_hz"] = FormatDouble(o.random_cutoff_hz);
      break;
    }
  }
}

// Edits (haptic_edits.h): per-shot model, washout, gain and mute, applied to
// the film model's samples before the film-level safety.

// Samples [begin, end) of each shot run: from its first frame up to the next
// run's first frame (the first run also takes any sample before it), the
// rule LabelSamples uses.
struct SampleRange {
  size_t begin = 0, end = 0;
};
std::vector<SampleRange> ShotSampleRanges(const CameraPath& path,
                                          const std::vector<ShotRange>& shots,
                                          const std::vector<double>& time_s) {
  std::vector<SampleRange> ranges(shots.size());
  for (size_t k = 1; k < shots.size(); ++k) {
    const double start = path.frames[shots[k].first].time_s;
    const auto first = std::lower_bound(time_s.begin(), time_s.end(), start);
    ranges[k].begin = ranges[k - 1].end = static_cast<size_t>(first - time_s.begin());
  }
  ranges.back().end = time_s.size();
  return ranges;
}

// A shot's effective options: the film's, with the shot's model and washout fields.
HapticOptions ShotOptions(const HapticOptions& o, const ShotEdit& e, const std::string& source) {
  HapticOptions s = o;
  if (e.model) s.model = *e.model;
  const std::string where = "edits: shot " + std::to_string(e.shot);
  if (!e.washout) return s;
  const WashoutEdit& w = *e.washout;
  try {
    if (w.mode) s.washout.mode = WashoutModeFromName(*w.mode);
    if (w.return_accel_m_s2) s.washout.return_accel_m_s2 = *w.return_accel_m_s2;
    if (w.window_s) s.washout.window_s = *w.window_s;
    if (w.tau_s) s.washout.tau_s = *w.tau_s;
    if (w.order) s.washout.order = *w.order;
    s.washout.Check();
  } catch (const UsageError& error) {
    throw Error(source, where + ": " + error.what());
  }
  return s;
}

bool SameWashout(const WashoutOptions& a, const WashoutOptions& b) {
  return a.mode == b.mode && a.tau_s == b.tau_s && a.order == b.order && a.window_s == b.window_s &&
         a.return_accel_m_s2 == b.return_accel_m_s2;
}

// Whether the shot's samples must be made again (its model or, for the
// cinematic model, its washout differs from the film's).
bool NeedsOwnModel(const HapticOptions& film, const HapticOptions& shot) {
  if (shot.model != film.model) return true;
  return shot.model == HapticModel::kCinematic && !SameWashout(film.washout, shot.washout);
}

// The cinematic model on shot run k alone, with the factors the whole path
// gets under this shot's washout (or the fixed ones), resampled at `out`'s times.
void CinematicShot(const CameraPath& path, const std::vector<ShotRange>& shots, size_t k,
                   const HapticOptions& s, std::vector<HapticSample>* out) {
  CameraPath one;
  one.metadata = path.metadata;
  one.frames.assign(path.frames.begin() + shots[k].first, path.frames.begin() + shots[k].last + 1);
  CinematicScaling scaling;
  if (s.cinematic_scaling) {
    scaling.per_shot.push_back(s.cinematic_scaling->ForShot(k));
  } else if (!s.cinematic.per_film_scaling) {
    // Per-shot factors depend on the shot alone: no pass over the whole film.
    scaling = ComputeCinematicScaling(one, s.seat, s.cinematic, s.washout);
  } else {
    scaling.per_shot.push_back(
        ComputeCinematicScaling(path, s.seat, s.cinematic, s.washout).ForShot(k));
  }
  const auto per_frame = CinematicFrames(one, s.seat, s.cinematic, s.washout, scaling);
  ResampleFrames(one, SplitShots(one), per_frame, out);
}

// Shot run k's samples made by its own model `s.model` (samples[r) replaced).
void RunShotModel(const CameraPath& path, const CameraPath& read_path,
                  const std::vector<ShotRange>& shots, size_t k, const SampleRange& r,
                  const std::vector<double>& time_s, const HapticOptions& s,
                  const std::vector<EffectSegment>& segs, std::vector<HapticSample>* samples,
                  std::vector<CameraEffect>* effects) {
  std::vector<HapticSample> out(samples->begin() + r.begin, samples->begin() + r.end);
  const std::vector<double> times(time_s.begin() + r.begin, time_s.begin() + r.end);
  for (HapticSample& x : out) {
    for (Eigen::Vector3d& p : x.pos_m) p.setZero();
  }
  std::vector<CameraEffect> shot_effects(times.size(), CameraEffect::kNone);
  if (s.model == HapticModel::kCinematic) CinematicShot(path, shots, k, s, &out);
  if (s.model == HapticModel::kSemantic) {
    CopyPositions(SemanticFrames(times, segs, s.seat, s.semantic, &shot_effects), &out);
  }
  if (s.model == HapticModel::kRandom) {
    RandomOptions random;  // each shot its own noise, faded in and out at its ends
    random.seed = RandomSeed(read_path, s) + static_cast<uint64_t>(k) + 1;
    random.cutoff_hz = s.random_cutoff_hz;
    CopyPositions(RandomFrames(times.size(), s.OutputRateHz(), s.seat, random), &out);
  }
  std::copy(out.begin(), out.end(), samples->begin() + r.begin);
  const bool any_effect = std::any_of(shot_effects.begin(), shot_effects.end(),
                                      [](CameraEffect e) { return e != CameraEffect::kNone; });
  if (effects->empty() && any_effect) effects->assign(time_s.size(), CameraEffect::kNone);
  if (!effects->empty())
    std::copy(shot_effects.begin(), shot_effects.end(), effects->begin() + r.begin);
}

// Throws Error(source) naming the first edited shot the path does not have.
void CheckEditedShotsExist(const std::vector<ShotRange>& shots, const HapticEdits& edits,
                           const std::string& source) {
  for (const ShotEdit& e : edits.shots) {
    if (std::none_of(shots.begin(), shots.end(),
                     [&](const ShotRange& r) { return r.shot == e.shot; })) {
      throw Error(source, "edits: shot " + std::to_string(e.shot) +
                              " is not in the camera path (its shots are " +
                              std::to_string(shots.front().shot) + " to " +
                              std::to_string(shots.back().shot) + ")");
    }
    if (!(e.Scale() >= 0 && e.Scale() <= kMaxShotGain)) {
      throw Error(source, "edits: shot " + std::to_string(e.shot) + ": gain must be in [0, 4]");
    }
  }
}

void ApplyEdits(const CameraPath& path, const CameraPath& read_path,
                const std::vector<ShotRange>& shots, const std::vector<double>& time_s,
                const HapticOptions& o, HapticTrack* track, std::vector<CameraEffect>* effects) {
  const std::string source = o.source.empty() ? "camera path" : o.source;
  CheckEditedShotsExist(shots, o.edits, source);
  const std::vector<SampleRange> ranges = ShotSampleRanges(path, shots, time_s);
  std::string edited;
  std::optional<std::vector<EffectSegment>> segs;  // made once, for the first semantic shot
  for (size_t k = 0; k < shots.size(); ++k) {
    const ShotEdit* e = o.edits.FindShot(shots[k].shot);
    if (!e) continue;
    const HapticOptions s = ShotOptions(o, *e, source);
    if (NeedsOwnModel(o, s)) {
      if (s.model == HapticModel::kSemantic && !segs) {
        segs = EffectSegmentsOfJoinedPath(path, s);
        track->metadata["effects_from"] = EffectsFrom(s);
      }
      RunShotModel(path, read_path, shots, k, ranges[k], time_s, s,
                   segs ? *segs : std::vector<EffectSegment>{}, &track->samples, effects);
    }
    const double scale = e->Scale();
    for (size_t i = ranges[k].begin; i < ranges[k].end && scale != 1.0; ++i) {
      for (Eigen::Vector3d& p : track->samples[i].pos_m) p *= scale;
    }
    edited += (edited.empty() ? "" : ";") + std::to_string(shots[k].shot);
  }
  if (!edited.empty()) track->metadata["edited_shots"] = edited;
}

}  // namespace

uint64_t DefaultRandomSeed(const CameraPath& path) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&](double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xff;
      h *= 0x100000001b3ull;
    }
  };
  for (const CameraFrame& f : path.frames) {
    mix(f.time_s);
    for (int k = 0; k < 3; ++k) mix(f.center[k]);
    const Eigen::Quaterniond& q = f.world_from_cam;
    for (double c : {q.w(), q.x(), q.y(), q.z()}) mix(c);
    mix(f.fov_deg);
    mix(f.shot ? *f.shot : -1.0);
  }
  return h;
}

const char* HapticModelName(HapticModel m) {
  switch (m) {
    case HapticModel::kCinematic:
      return "cinematic";
    case HapticModel::kSemantic:
      return "semantic";
    case HapticModel::kRandom:
      return "random";
    case HapticModel::kNone:
      return "none";
  }
  return "?";
}

HapticModel HapticModelFromName(const std::string& name) {
  for (HapticModel m : {HapticModel::kCinematic, HapticModel::kSemantic, HapticModel::kRandom,
                        HapticModel::kNone}) {
    if (name == HapticModelName(m)) return m;
  }
  throw UsageError("unknown haptic model '" + name +
                   "' (expected cinematic, semantic, random or none)");
}

void HapticOptions::Check() const {
  seat.Check();
  if (!(rate_hz == 0 || (rate_hz >= 10 && rate_hz <= 10000))) {
    throw UsageError("rate must be in [10, 10000] Hz");
  }
  washout.Check();
  cinematic.Check();
  semantic.Check();
  classifier.Check();
  RandomOptions r;
  r.cutoff_hz = random_cutoff_hz;
  r.Check();
  if (!(random_cutoff_hz < OutputRateHz() / 4)) {
    throw UsageError("random cutoff must be below a quarter of the output rate");
  }
  if (!(max_gap_s > 0 && max_gap_s <= 600)) throw UsageError("max gap must be in (0, 600] s");
  const bool semantic_shot =
      std::any_of(edits.shots.begin(), edits.shots.end(),
                  [](const ShotEdit& e) { return e.model == HapticModel::kSemantic; });
  if (!keyframes_file.empty() && model != HapticModel::kSemantic && !semantic_shot) {
    throw UsageError("keyframes only apply to the semantic model");
  }
}

HapticTrack MakeHapticTrack(const CameraPath& read_path, const HapticOptions& o) {
  o.Check();
  const std::string source = o.source.empty() ? "camera path" : o.source;
  ValidatePathForHaptics(read_path, source, o.max_gap_s);
  // The models never integrate lost frames: the pose gap after them is
  // closed here (JoinAcrossLostFrames), and the cinematic model returns the
  // actuators to rest over them (cinematic_model.cc).
  const std::optional<CameraPath> joined = JoinAcrossLostFrames(read_path);
  const CameraPath& path = joined ? *joined : read_path;
  if (std::abs(path.frames.front().time_s) > kMaxMediaClockS) {
    // Times counted from the first frame instead; the offset is kept.
    CameraPath from_first = path;
    for (CameraFrame& f : from_first.frames) f.time_s -= path.frames.front().time_s;
    HapticTrack track = MakeHapticTrack(from_first, o);
    track.metadata["time_origin_s"] = FormatDouble(path.frames.front().time_s);
    return track;
  }
  const double rate = o.OutputRateHz();
  std::vector<double> time_s = SampleTimes(path, rate, source);
  const size_t regular_rows = time_s.size();

  const std::vector<ShotRange> shots = SplitShots(path);
  const std::vector<double> cut_times = CutTimes(path, shots);
  const std::vector<EffectSegment> segs = SemanticSegments(path, o);
  if (UsesSemantic(o)) time_s = SemanticSampleTimes(std::move(time_s), segs, cut_times, o);
  const size_t n = time_s.size();

  HapticTrack track;
  track.rate_hz = rate;
  track.interpolation = InterpolationForRate(rate);
  track.model = HapticModelName(o.model);
  track.source = o.source;
  // The samples are built in place (a two-hour film is 7.2 million of
  // them): a model's frames, when it makes any, are copied in and freed.
  track.samples.resize(n);
  for (size_t i = 0; i < n; ++i) track.samples[i].time_s = time_s[i];
  std::vector<CameraEffect> effects;
  RunFilmModel(path, read_path, shots, time_s, segs, o, &track, &effects);
  if (n > regular_rows) track.metadata["dense_rows"] = std::to_string(n - regular_rows);
  if (!o.edits.empty()) ApplyEdits(path, read_path, shots, time_s, o, &track, &effects);
  ApplyCutTransitions(time_s, cut_times, o.washout.cut_ramp_s, &track.samples);
  const int limited = LimitSpeed(o.washout.max_speed_m_s, rate, &track.samples);
  const int clamped = ClampToWorkspace(o.seat.clamp_half_m, &track.samples);
  // The washout acts on camera motion, i.e. on the cinematic model only.
  const WashoutMode washout =
      o.model == HapticModel::kCinematic ? o.washout.mode : WashoutMode::kOff;
  track.metadata["washout"] = WashoutModeName(washout);
  if (washout == WashoutMode::kHighPass) {
    track.metadata["washout_tau_s"] = FormatDouble(o.washout.tau_s);
    track.metadata["washout_order"] = std::to_string(o.washout.order);
  }
  track.metadata["max_step_m"] = FormatDouble(o.washout.max_speed_m_s / rate);
  track.metadata["rate_limited_samples"] = std::to_string(limited);
  track.metadata["clamped_samples"] = std::to_string(clamped);
  const std::vector<ShotConfidence> quality =
      AssessShotConfidence(read_path, SplitShots(read_path));
  track.metadata["low_quality_shots"] = std::to_string(
      std::count_if(quality.begin(), quality.end(), [](const ShotConfidence& c) { return c.low; }));
  LabelSamples(path, shots, effects, &track.samples);
  return track;
}

HapticDifference HapticTrackDifference(const HapticTrack& a, const HapticTrack& b) {
  HapticDifference d;
  if (a.samples.empty() || b.samples.empty()) return d;
  const double lo = b.samples.front().time_s, hi = b.samples.back().time_s;
  double sum_sq[kNumActuators] = {0, 0, 0};
  size_t hint = 0;
  Eigen::Vector3d pb[kNumActuators];
  for (const HapticSample& s : a.samples) {
    if (s.time_s < lo - 1e-9 || s.time_s > hi + 1e-9) continue;
    b.Sample(s.time_s, pb, &hint);
    for (int k = 0; k < kNumActuators; ++k) {
      const double e = (s.pos_m[k] - pb[k]).norm();
      sum_sq[k] += e * e;
      d.max_m[k] = std::max(d.max_m[k], e);
    }
    ++d.num_samples;
  }
  if (d.num_samples > 0) {
    for (int k = 0; k < kNumActuators; ++k) d.rms_m[k] = std::sqrt(sum_sq[k] / d.num_samples);
  }
  return d;
}

std::pair<HapticTrack, HapticTrack> MakeComparableHapticTracks(const CameraPath& reference,
                                                               const CameraPath& other,
                                                               HapticOptions o) {
  if (!o.seed) o.seed = DefaultRandomSeed(reference);  // one noise for both
  if (o.model == HapticModel::kCinematic && !o.cinematic_scaling) {
    o.Check();
    ValidatePathForHaptics(reference, o.source.empty() ? "reference camera path" : o.source,
                           o.max_gap_s);
    o.cinematic_scaling = ComputeCinematicScaling(reference, o.seat, o.cinematic, o.washout);
  }
  HapticTrack a = MakeHapticTrack(reference, o);
  HapticTrack b = MakeHapticTrack(other, o);
  return {std::move(a), std::move(b)};
}

}  // namespace hapcine

namespace hapcine {

void CheckEditsForPath(const CameraPath& path, const HapticOptions& options) {
  const std::string source = options.source.empty() ? "camera path" : options.source;
  CheckEditedShotsExist(SplitShots(path), options.edits, source);
  for (const ShotEdit& e : options.edits.shots) ShotOptions(options, e, source);
}

std::vector<EffectSegment> EffectiveEffectSegments(const CameraPath& path,
                                                   const HapticOptions& options) {
  const std::optional<CameraPath> joined = JoinAcrossLostFrames(path);
  return EffectSegmentsOfJoinedPath(joined ? *joined : path, options);
}

}  // namespace hapcine
