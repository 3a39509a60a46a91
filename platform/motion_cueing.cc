#include "platform/motion_cueing.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/rotation.h"
#include "haptics/camera_signals.h"
#include "haptics/cinematic_model.h"
#include "platform/platform_safety.h"
#include "platform/stewart.h"

namespace hapcine {
namespace {

constexpr double kGravity = 9.81;  // m/s^2

// The camera signals on the output grid: per sample its shot (order in the
// path), whether a cut starts there, and the six raw channels (path units
// for sway/heave/surge, radians for pitch/yaw/roll, before scaling).
struct CueGrid {
  double dt = 0.01;
  std::vector<double> time_s;
  std::vector<int> shot;         // index into the shot list
  std::vector<char> cut;         // first sample of a shot after the first
  std::vector<PlatformPose> raw;
  size_t size() const { return time_s.size(); }
};

double Interpolate(const std::vector<double>& t, const std::vector<double>& v, double at,
                   size_t* hint) {
  if (at <= t.front()) return v.front();
  if (at >= t.back()) return v.back();
  size_t i = std::min(*hint, t.size() - 2);
  if (t[i] > at) i = 0;
  while (t[i + 1] < at) ++i;
  *hint = i;
  const double w = (at - t[i]) / (t[i + 1] - t[i]);
  return v[i] + w * (v[i + 1] - v[i]);
}

// Split the per-shot position vectors once, so sampling is O(1) per channel.
struct ShotChannels {
  std::vector<double> time_s;
  std::vector<double> v[kNumDofs];
};

ShotChannels ChannelsOf(const CameraSignals& s) {
  ShotChannels c;
  c.time_s = s.time_s;
  for (auto& v : c.v) v.resize(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    c.v[0][i] = s.position_u[i].x();
    c.v[1][i] = s.position_u[i].y();
    c.v[2][i] = s.position_u[i].z() - s.zoom_forward_u[i];  // Eq. 6: zoom-in = forward (-Z)
    c.v[3][i] = s.tilt_rad[i];
    c.v[4][i] = s.pan_rad[i];
    c.v[5][i] = s.roll_rad[i];
  }
  return c;
}

CueGrid SampleSignals(const CameraPath& path, const std::vector<ShotRange>& shots,
                      const std::vector<CameraSignals>& signals, double rate_hz) {
  CueGrid g;
  g.dt = 1.0 / rate_hz;
  const double t0 = path.frames.front().time_s, t1 = path.frames.back().time_s;
  const long n = static_cast<long>(std::floor((t1 - t0) * rate_hz + 1e-9)) + 1;
  std::vector<ShotChannels> channels;
  for (const auto& s : signals) channels.push_back(ChannelsOf(s));
  size_t k = 0, hint = 0;
  for (long i = 0; i < n; ++i) {
    const double t = t0 + i * g.dt;
    bool cut = false;
    while (k + 1 < shots.size() && path.frames[shots[k + 1].first].time_s <= t + 1e-9) {
      ++k;
      hint = 0;
      cut = true;
    }
    PlatformPose raw;
    for (int d = 0; d < kNumDofs; ++d) {
      size_t h = hint;
      raw[d] = Interpolate(channels[k].time_s, channels[k].v[d], t, &h);
      if (d == kNumDofs - 1) hint = h;
    }
    g.time_s.push_back(t);
    g.shot.push_back(static_cast<int>(k));
    g.cut.push_back(cut && i > 0);
    g.raw.push_back(raw);
  }
  return g;
}

struct ReturnLimits {
  double accel = 0, speed = 0;
};

struct ChannelParams {
  ReturnLimits slow, fast;  // outside / inside a cut's window
  double still = 0;         // signal speed below which the camera counts as still
  double cut_window_s = 0;
  double dt = 0.01;
};

// The signal's speed over the last kSpeedWindowS (a window, so that
// estimation noise does not read as motion), restarting at cuts, and the
// still threshold per sample: the absolute one, or 2 % of the shot's
// fastest speed when that is lower (a long shot scaled down to fit moves
// slowly all along; its ease-out is still motion).
constexpr double kSpeedWindowS = 0.25;
constexpr double kStillFractionOfPeak = 0.02;

void WindowedSpeed(const std::vector<double>& c, const std::vector<char>& cut,
                   const ChannelParams& p, std::vector<double>* speed,
                   std::vector<double>* still) {
  const size_t n = c.size();
  const size_t lag = std::max<size_t>(1, static_cast<size_t>(std::lround(kSpeedWindowS / p.dt)));
  speed->assign(n, 0.0);
  still->assign(n, p.still);
  size_t shot_start = 0;
  for (size_t i = 0; i <= n; ++i) {
    if (i == n || (i > 0 && cut[i])) {  // close the shot [shot_start, i)
      double peak = 0;
      for (size_t j = shot_start; j < i; ++j) peak = std::max(peak, std::abs((*speed)[j]));
      for (size_t j = shot_start; j < i; ++j)
        (*still)[j] = std::min(p.still, kStillFractionOfPeak * peak);
      shot_start = i;
      if (i == n) break;
    }
    const size_t from = std::max(shot_start, i >= lag ? i - lag : 0);
    (*speed)[i] = i > from ? (c[i] - c[from]) / ((i - from) * p.dt) : 0.0;
  }
}

// The platform's position for one DOF: the scaled camera signal c minus a
// return r that brings it home without false cues (motion_cueing.h).
// Starts at home; at a cut (cut[i]) the signal restarts from the new shot's
// first frame and r absorbs the jump, so the pose is continuous. While the
// signal moves, a return may only go the camera's way.
std::vector<double> FollowWithReturns(const std::vector<double>& c, const std::vector<char>& cut,
                                      const ChannelParams& p) {
  std::vector<double> out(c.size()), speed, still;
  WindowedSpeed(c, cut, p, &speed, &still);
  double r = c.empty() ? 0 : c[0], u = 0, window = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    if (i > 0 && cut[i]) {
      r += c[i] - c[i - 1];
      window = p.cut_window_s;
    }
    const double s = speed[i];
    const ReturnLimits& lim = window > 0 ? p.fast : p.slow;
    const double e = c[i] - r;  // the pose without a further return
    const double u_want = std::copysign(std::min(lim.speed, std::sqrt(2 * lim.accel * std::abs(e))), e);
    // Leaving a cut's window, a fast return slows down at the fast rate.
    const double accel = std::abs(u) > lim.speed ? p.fast.accel : lim.accel;
    u = std::clamp(u_want, u - accel * p.dt, u + accel * p.dt);
    if (window <= 0 && std::abs(s) > still[i]) u = s > 0 ? std::min(u, 0.0) : std::max(u, 0.0);
    if (u * e > 0 && std::abs(u * p.dt) > std::abs(e)) u = e / p.dt;  // no overshoot of home
    r += u * p.dt;
    window -= p.dt;
    out[i] = c[i] - r;
  }
  return out;
}

ChannelParams ParamsFor(const PlatformConfig& cfg, int dof, double dt) {
  const CueingParams& q = cfg.cueing;
  ChannelParams p;
  p.dt = dt;
  p.cut_window_s = q.cut_ramp_s;
  p.slow = IsRotation(dof) ? ReturnLimits{q.return_accel_rad_s2, q.return_rate_rad_s}
                           : ReturnLimits{q.return_accel_m_s2, q.return_speed_m_s};
  p.fast = {0.5 * cfg.limits[dof].acceleration, 0.5 * cfg.limits[dof].velocity};
  p.slow.accel = std::min(p.slow.accel, p.fast.accel);
  p.slow.speed = std::min(p.slow.speed, p.fast.speed);
  p.still = IsRotation(dof) ? q.still_rate_rad_s : q.still_speed_m_s;
  return p;
}

// The tilt coordination's share of pitch and roll (0 for other DOFs).
double TiltBudget(const PlatformConfig& cfg, int dof) {
  if (dof != static_cast<int>(Dof::kPitch) && dof != static_cast<int>(Dof::kRoll)) return 0;
  if (!cfg.enabled[dof]) return 0;
  return std::min(cfg.cueing.tilt_max_rad,
                  0.25 * cfg.cueing.usable_fraction * cfg.limits[dof].position);
}

double UsableRange(const PlatformConfig& cfg, int dof) {
  return cfg.cueing.usable_fraction * cfg.limits[dof].position - TiltBudget(cfg, dof);
}

// Pitch and roll from the low-passed horizontal specific force, rate
// limited; zero for DOFs the platform does not have.
std::vector<PlatformPose> TiltCoordination(const CueGrid& g, const PlatformConfig& cfg) {
  const CueingParams& q = cfg.cueing;
  std::vector<PlatformPose> tilt(g.size(), PlatformPose::Zero());
  const int pitch = static_cast<int>(Dof::kPitch), roll = static_cast<int>(Dof::kRoll);
  const double budget[2] = {TiltBudget(cfg, pitch), TiltBudget(cfg, roll)};
  if (budget[0] <= 0 && budget[1] <= 0) return tilt;
  // Surge (z) and sway (x) specific force, m/s^2, through two first-order
  // sections of tilt_lowpass_s / 2 each: the camera's frames make the
  // acceleration on the output grid a train of impulses, which one section
  // would leave as a ripple in the tilt.
  double force_lp[2] = {0, 0}, force_lp1[2] = {0, 0};
  double angle[2] = {0, 0};  // pitch, roll
  const double alpha = g.dt / (0.5 * q.tilt_lowpass_s + g.dt);
  for (size_t i = 1; i + 1 < g.size(); ++i) {
    const bool inside = !g.cut[i] && !g.cut[i + 1];
    for (int k = 0; k < 2; ++k) {
      const int axis = k == 0 ? 2 : 0;
      const double acc =
          inside ? (g.raw[i + 1][axis] - 2 * g.raw[i][axis] + g.raw[i - 1][axis]) / (g.dt * g.dt)
                 : 0.0;
      force_lp1[k] += alpha * (q.specific_force_gain * acc - force_lp1[k]);
      force_lp[k] += alpha * (force_lp1[k] - force_lp[k]);
      // Forward (-z) acceleration: front up; rightward (+x): right side up.
      const double f = k == 0 ? -force_lp[k] : force_lp[k];
      const double target = std::asin(std::clamp(f / kGravity, -1.0, 1.0));
      const double want = std::clamp(target, -budget[k], budget[k]);
      const double step = q.tilt_rate_rad_s * g.dt;
      angle[k] += std::clamp(want - angle[k], -step, step);
    }
    tilt[i][pitch] = angle[0];
    tilt[i][roll] = angle[1];
  }
  return tilt;
}

// Largest |pose| / usable over DOFs `dofs` of one shot with gain g.
double PeakRatio(const CueGrid& g, size_t begin, size_t end, const std::vector<int>& dofs,
                 const PlatformConfig& cfg, double gain) {
  double ratio = 0;
  const std::vector<char> no_cuts(end - begin, 0);
  std::vector<double> c(end - begin);
  for (int d : dofs) {
    for (size_t i = begin; i < end; ++i) c[i - begin] = gain * g.raw[i][d];
    const std::vector<double> p = FollowWithReturns(c, no_cuts, ParamsFor(cfg, d, g.dt));
    double peak = 0;
    for (double v : p) peak = std::max(peak, std::abs(v));
    ratio = std::max(ratio, peak / UsableRange(cfg, d));
  }
  return ratio;
}

// The largest gain in [0, cap] whose peak ratio is <= 1: a grid (the peak
// need not be monotone in the gain once returns act), then bisection.
double FitGain(const CueGrid& g, size_t begin, size_t end, const std::vector<int>& dofs,
               const PlatformConfig& cfg, double cap) {
  if (dofs.empty() || PeakRatio(g, begin, end, dofs, cfg, cap) <= 1) return cap;
  constexpr int kGrid = 24;
  double lo = 0, hi = cap;
  for (int j = 1; j <= kGrid; ++j) {
    const double gain = cap * j / kGrid;
    if (PeakRatio(g, begin, end, dofs, cfg, gain) > 1) {
      hi = gain;
      break;
    }
    lo = gain;
  }
  for (int it = 0; it < 20; ++it) {
    const double mid = 0.5 * (lo + hi);
    (PeakRatio(g, begin, end, dofs, cfg, mid) > 1 ? hi : lo) = mid;
  }
  return lo;
}

// The poses of one shot alone (from home, no cut) with the given scale.
std::vector<PlatformPose> ShotPoses(const CueGrid& g, size_t begin, size_t end,
                                    const PlatformConfig& cfg, const PlatformShotScale& scale,
                                    const std::vector<PlatformPose>& tilt) {
  std::vector<PlatformPose> pose(tilt.begin() + begin, tilt.begin() + end);
  const std::vector<char> no_cuts(end - begin, 0);
  std::vector<double> c(end - begin);
  for (int d = 0; d < kNumDofs; ++d) {
    if (!cfg.enabled[d]) continue;
    const double gain = IsRotation(d) ? scale.rotation_gain : scale.translation_m_per_u;
    for (size_t i = begin; i < end; ++i) c[i - begin] = gain * g.raw[i][d];
    const std::vector<double> p = FollowWithReturns(c, no_cuts, ParamsFor(cfg, d, g.dt));
    for (size_t i = 0; i < p.size(); ++i) pose[i][d] += p[i];
  }
  return pose;
}

double StrokeMargin(const PlatformConfig& cfg) {
  const StewartGeometry& st = *cfg.stewart;
  return 0.5 * (1 - cfg.cueing.usable_fraction) * (st.max_leg_m - st.min_leg_m);
}

bool ShotFitsStroke(const CueGrid& g, size_t begin, size_t end, const PlatformConfig& cfg,
                    const PlatformShotScale& scale, const std::vector<PlatformPose>& tilt) {
  for (const PlatformPose& p : ShotPoses(g, begin, end, cfg, scale, tilt)) {
    if (!LegsWithinStroke(*cfg.stewart, StewartLegLengths(*cfg.stewart, p), StrokeMargin(cfg)))
      return false;
  }
  return true;
}

// A Stewart platform's DOFs share the legs: the per-DOF gains can ask for
// poses no leg reaches. Both gains shrink by one factor (bisection) until the
// whole shot fits the usable stroke, so the pose is never scaled back while
// the camera keeps moving (which would be a false cue).
PlatformShotScale FitStroke(const CueGrid& g, size_t begin, size_t end, const PlatformConfig& cfg,
                            const PlatformShotScale& scale, const std::vector<PlatformPose>& tilt) {
  if (!cfg.stewart || ShotFitsStroke(g, begin, end, cfg, scale, tilt)) return scale;
  double lo = 0, hi = 1;
  for (int it = 0; it < 16; ++it) {
    const double mid = 0.5 * (lo + hi);
    const PlatformShotScale s{mid * scale.translation_m_per_u, mid * scale.rotation_gain};
    (ShotFitsStroke(g, begin, end, cfg, s, tilt) ? lo : hi) = mid;
  }
  return {lo * scale.translation_m_per_u, lo * scale.rotation_gain};
}

std::vector<PlatformShotScale> FitShotScales(const CueGrid& g, size_t num_shots,
                                             const PlatformConfig& cfg,
                                             const std::vector<PlatformPose>& tilt) {
  std::vector<int> translations, rotations;
  double min_usable = 1e9;
  for (int d = 0; d < kNumDofs; ++d) {
    if (!cfg.enabled[d] || UsableRange(cfg, d) <= 0) continue;
    (IsRotation(d) ? rotations : translations).push_back(d);
    if (!IsRotation(d)) min_usable = std::min(min_usable, UsableRange(cfg, d));
  }
  const double k_cap = translations.empty() ? 0 : min_usable / cfg.cueing.fill_motion_u;
  std::vector<PlatformShotScale> scales(num_shots);
  size_t begin = 0;
  while (begin < g.size()) {
    size_t end = begin + 1;
    while (end < g.size() && g.shot[end] == g.shot[begin]) ++end;
    PlatformShotScale& s = scales[g.shot[begin]];
    s.translation_m_per_u = FitGain(g, begin, end, translations, cfg, k_cap);
    s.rotation_gain = FitGain(g, begin, end, rotations, cfg, 1.0);
    s = FitStroke(g, begin, end, cfg, s, tilt);
    begin = end;
  }
  return scales;
}

std::vector<PlatformPose> DesiredPoses(const CueGrid& g, const PlatformConfig& cfg,
                                       const std::vector<PlatformShotScale>& scales,
                                       std::vector<PlatformPose> pose /* the tilt */) {
  std::vector<double> c(g.size());
  for (int d = 0; d < kNumDofs; ++d) {
    if (!cfg.enabled[d]) continue;
    for (size_t i = 0; i < g.size(); ++i) {
      const PlatformShotScale& s = scales[g.shot[i]];
      c[i] = (IsRotation(d) ? s.rotation_gain : s.translation_m_per_u) * g.raw[i][d];
    }
    const std::vector<double> p = FollowWithReturns(c, g.cut, ParamsFor(cfg, d, g.dt));
    for (size_t i = 0; i < g.size(); ++i) pose[i][d] += p[i];
  }
  if (cfg.stewart) {
    // Into the usable stroke, towards home (the clamp's margin stays free):
    // only where shots meet (FitStroke fitted each shot alone).
    for (auto& p : pose) p *= StrokeScale(*cfg.stewart, p, StrokeMargin(cfg));
  }
  return pose;
}

std::string DofList(const PlatformConfig& cfg) {
  std::string out;
  for (int d = 0; d < kNumDofs; ++d) {
    if (cfg.enabled[d]) out += (out.empty() ? "" : " ") + std::string(DofName(static_cast<Dof>(d)));
  }
  return out;
}

PlatformTrack SafeTrack(const CameraPath& path, const CueGrid& g, const PlatformConfig& cfg,
                        const std::vector<PlatformPose>& desired, double rate_hz) {
  PlatformTrack track;
  track.rate_hz = rate_hz;
  track.platform = cfg.name;
  track.dofs = DofList(cfg);
  PlatformSafety safety(cfg, rate_hz);
  const std::vector<ShotRange> shots = SplitShots(path);
  for (size_t i = 0; i < g.size(); ++i) {
    PlatformSample s;
    s.time_s = g.time_s[i];
    s.pose = safety.Step(desired[i]);
    if (cfg.stewart) s.legs = StewartLegLengths(*cfg.stewart, s.pose);
    const std::optional<int>& shot = path.frames[shots[g.shot[i]].first].shot;
    if (shot) s.shot = *shot;
    track.samples.push_back(std::move(s));
  }
  const SafetyCounts& n = safety.counts();
  track.metadata["clamped_samples"] = std::to_string(n.clamped);
  track.metadata["stroke_limited_samples"] = std::to_string(n.stroke_limited);
  track.metadata["nonfinite_samples"] = std::to_string(n.nonfinite);
  return track;
}

}  // namespace

void PlatformOptions::Check() const {
  if (model != "cinematic" && model != "none")
    throw UsageError("a motion platform takes --model cinematic or none");
  if (!(reference_depth_u >= 0 && std::isfinite(reference_depth_u)))
    throw UsageError("reference depth must be >= 0 (0 = automatic)");
  if (rate_hz != 0 && !(rate_hz >= 10 && rate_hz <= 10000))
    throw UsageError("platform rate must be 0 (the config's) or in [10, 10000] Hz");
}

PlatformTrack MakePlatformTrack(const CameraPath& path, const PlatformConfig& cfg,
                                const PlatformOptions& o, std::vector<PlatformShotScale>* scales_out) {
  o.Check();
  cfg.Check();
  if (path.frames.empty()) throw Error(o.source, "camera path has no frames");
  const double rate = o.rate_hz > 0 ? o.rate_hz : cfg.rate_hz;
  const std::vector<ShotRange> shots = SplitShots(path);
  CinematicOptions copt;
  copt.reference_depth_u = o.reference_depth_u;
  WashoutOptions wopt;
  wopt.mode = WashoutMode::kOff;  // the returns below replace the washout
  wopt.cut_ramp_s = cfg.cueing.cut_ramp_s;
  const CueGrid grid = SampleSignals(path, shots, CinematicShotSignals(path, shots, copt, wopt), rate);
  std::vector<PlatformShotScale> scales(shots.size());
  std::vector<PlatformPose> desired(grid.size(), PlatformPose::Zero());
  if (o.model == "cinematic") {
    std::vector<PlatformPose> tilt = TiltCoordination(grid, cfg);
    scales = FitShotScales(grid, shots.size(), cfg, tilt);
    desired = DesiredPoses(grid, cfg, scales, std::move(tilt));
  }
  PlatformTrack track = SafeTrack(path, grid, cfg, desired, rate);
  track.model = o.model;
  track.source = o.source;
  track.metadata["return_accel_m_s2"] = std::to_string(cfg.cueing.return_accel_m_s2);
  track.metadata["return_rate_deg_s"] = std::to_string(RadToDeg(cfg.cueing.return_rate_rad_s));
  track.metadata["tilt_rate_deg_s"] = std::to_string(RadToDeg(cfg.cueing.tilt_rate_rad_s));
  if (scales_out) *scales_out = scales;
  return track;
}

}  // namespace hapcine
