#include "haptics/cinematic_model.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "haptics/confidence.h"

namespace hapcine {
namespace {

Eigen::Matrix3d Rotation(double tilt, double pan, double roll) {
  // Equation 5's order: Rx(phi) Ry(theta) Rz(psi).
  return (Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

// Largest coordinate of any R_A over the shot for rotation gain m.
double MaxRotationOffset(const CameraSignals& s, const SeatGeometry& seat, double m) {
  double peak = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const Eigen::Matrix3d r = Rotation(m * s.tilt_rad[i], m * s.pan_rad[i], m * s.roll_rad[i]) -
                              Eigen::Matrix3d::Identity();
    for (int a = 0; a < kNumActuators; ++a) {
      peak = std::max(peak, (r * seat.FromCenter(a)).cwiseAbs().maxCoeff());
    }
  }
  return peak;
}

// Largest coordinate of f (Equation 3) over the shot, any actuator.
double MaxCombinedOffset(const CameraSignals& s, const SeatGeometry& seat,
                         const CinematicScale& c) {
  double peak = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const ActuatorFrame f = CinematicDisplacement(s.position_u[i], s.tilt_rad[i], s.pan_rad[i],
                                                  s.roll_rad[i], s.zoom_forward_u[i], c, seat);
    for (const auto& v : f) peak = std::max(peak, v.cwiseAbs().maxCoeff());
  }
  return peak;
}

CinematicScale Scaled(const CinematicScale& c, double gain) {
  CinematicScale out = c;
  out.kx = out.ky = out.kz = out.sz = gain * c.kx;
  out.mx = out.my = out.mz = gain * c.mx;
  return out;
}

// T, R and F were each sized to fill the usable range on their own, but f
// averages them (weights |T|, |R|, |F|): when they point different ways (a
// crane that tilts down to keep its subject framed) the actuators use only
// part of their range. f is what they render, so k, sz and m are raised
// together by the largest gain that keeps every coordinate of f within
// usable (grid, then bisection, as for m), within the caps and at most
// kMaxCombinationGain: three vectors that each fill the range along
// different axes average down to a third; a larger shortfall comes from
// vectors that oppose each other, which is the cancellation the paper wants
// (Vertigo) and must not be amplified back. Returns the gain (>= 1).
constexpr double kMaxCombinationGain = 3.0;

double CombinationGain(const CameraSignals& s, const SeatGeometry& seat, const CinematicOptions& o,
                       const CinematicScale& c) {
  double max_gain = kMaxCombinationGain;
  if (c.kx > 0) max_gain = std::min(max_gain, o.max_translation_gain / c.kx);
  if (c.mx > 0) max_gain = std::min(max_gain, o.max_rotation_gain / c.mx);
  const double usable = seat.usable_half_m;
  if (!(max_gain > 1) || !(MaxCombinedOffset(s, seat, c) > 0)) return 1.0;
  constexpr int kGrid = 32;
  double lo = 1, hi = -1;
  for (int j = 1; j <= kGrid; ++j) {
    const double g = 1 + (max_gain - 1) * j / kGrid;
    if (MaxCombinedOffset(s, seat, Scaled(c, g)) > usable) {
      hi = g;
      break;
    }
    lo = g;
  }
  if (hi > 0) {
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (lo + hi);
      (MaxCombinedOffset(s, seat, Scaled(c, mid)) > usable ? hi : lo) = mid;
    }
  }
  return lo;
}

// k and m such that T, F and every R_A each stay within the usable range
// (before the combination gain).
CinematicScale BaseScaleForShot(const CameraSignals& s, const SeatGeometry& seat,
                                const CinematicOptions& o) {
  const double usable = seat.usable_half_m;
  double peak_t = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    peak_t =
        std::max({peak_t, s.position_u[i].cwiseAbs().maxCoeff(), std::abs(s.zoom_forward_u[i])});
  }
  const double k =
      peak_t > usable / o.max_translation_gain ? usable / peak_t : o.max_translation_gain;
  // Rotation gain: the first m on a grid where the offset exceeds the usable
  // range, refined by bisection (R is not monotone in m for large angles,
  // hence the grid rather than a bisection over the whole interval).
  constexpr int kGrid = 64;
  double lo = 0, hi = -1;
  for (int j = 1; j <= kGrid; ++j) {
    const double m = o.max_rotation_gain * j / kGrid;
    if (MaxRotationOffset(s, seat, m) > usable) {
      hi = m;
      break;
    }
    lo = m;
  }
  double m = lo;
  if (hi > 0) {
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (MaxRotationOffset(s, seat, mid) > usable ? hi : lo) = mid;
    }
    m = lo;
  }
  CinematicScale c;
  c.kx = c.ky = c.kz = c.sz = k;
  c.mx = c.my = c.mz = m;
  return c;
}

// Lost frames are no motion: the actuators return to rest over them with
// the cut crossfade's ramp (FadeToRestOverLostFrames).
void FadeOverLostFrames(const CameraPath& path, const ShotRange& r, double ramp_s,
                        CameraSignals* s) {
  std::vector<bool> lost(s->size());
  bool any = false;
  for (size_t i = 0; i < s->size(); ++i) any |= lost[i] = IsLost(path.frames[r.first + i]);
  if (!any) return;
  std::vector<double> ch(s->size());
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < s->size(); ++i) ch[i] = s->position_u[i][k];
    FadeToRestOverLostFrames(s->time_s, lost, ramp_s, &ch);
    for (size_t i = 0; i < s->size(); ++i) s->position_u[i][k] = ch[i];
  }
  for (auto* v : {&s->tilt_rad, &s->pan_rad, &s->roll_rad, &s->zoom_forward_u, &s->log_zoom})
    FadeToRestOverLostFrames(s->time_s, lost, ramp_s, v);
}

// `base` with translation/zoom and rotation gains raised by `gain`, each
// within its cap (a shot without rotation is already at the rotation cap).
CinematicScale Raised(const CinematicScale& base, double gain, const CinematicOptions& o) {
  CinematicScale c = base;
  const double k = base.kx > 0 ? std::min(gain * base.kx, o.max_translation_gain) : 0.0;
  const double m = base.mx > 0 ? std::min(gain * base.mx, o.max_rotation_gain) : 0.0;
  c.kx = c.ky = c.kz = c.sz = std::max(k, base.kx);
  c.mx = c.my = c.mz = std::max(m, base.mx);
  return c;
}

// Equations 2-6 over one shot's signals.
std::vector<ActuatorFrame> ShotFrames(const CameraSignals& s, const CinematicScale& c,
                                      const SeatGeometry& seat) {
  std::vector<ActuatorFrame> out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    out.push_back(CinematicDisplacement(s.position_u[i], s.tilt_rad[i], s.pan_rad[i], s.roll_rad[i],
                                        s.zoom_forward_u[i], c, seat));
  }
  return out;
}

// The shot's frames with a return of time constant tau_s (0 = none).
std::vector<ActuatorFrame> Returned(const CameraSignals& s, std::vector<ActuatorFrame> f,
                                    double tau_s, const WashoutOptions& w) {
  if (tau_s > 0) {
    const double still = StillSpeed(s.time_s, f, w.still_fraction);
    ApplyReturnToCentre(s.time_s, still, tau_s, w.return_accel_m_s2, &f);
  }
  return f;
}

// The slowest return (largest time constant in [kMinReturnTauS, shot
// length]) that keeps the shot within the usable range at `gain` over
// `base`; 0 when even the fastest does not.
constexpr double kMinReturnTauS = 0.5;

double SlowestFittingReturn(const CameraSignals& s, const CinematicScale& base, double gain,
                            const SeatGeometry& seat, const CinematicOptions& o,
                            const WashoutOptions& w) {
  const std::vector<ActuatorFrame> plain = ShotFrames(s, Raised(base, gain, o), seat);
  auto fits = [&](double tau) {
    return PeakCoordinate(Returned(s, plain, tau, w)) <= seat.usable_half_m;
  };
  const double longest = std::max(kMinReturnTauS, s.time_s.back() - s.time_s.front());
  if (fits(longest)) return longest;
  if (!fits(kMinReturnTauS)) return 0;
  double lo = kMinReturnTauS, hi = longest;
  for (int it = 0; it < 24; ++it) {
    const double mid = std::sqrt(lo * hi);  // time constants span decades
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

// Adaptive washout for one shot whose per-shot scaling is `base`: the plain
// Equations 2-6 when scaling alone keeps at least 1 / min_gain of the gain
// the shot's motion within window_s would get; otherwise that gain (within
// the caps), or the largest below it that a return can fit, with the
// slowest fitting return.
CinematicScale AdaptiveReturnForShot(const CameraSignals& s, const SeatGeometry& seat,
                                     const CinematicOptions& o, const WashoutOptions& w,
                                     const CinematicScale& base) {
  if (s.size() < 3) return base;
  const std::vector<ActuatorFrame> plain = ShotFrames(s, base, seat);
  const double peak = PeakCoordinate(plain);
  const double window_range = LargestWindowRange(s.time_s, plain, w.window_s);
  if (!(window_range > 0) || peak < w.min_gain * window_range) return base;
  double gain = peak / window_range;
  const double k_room = base.kx > 0 ? o.max_translation_gain / base.kx : 0.0;
  const double m_room = base.mx > 0 ? o.max_rotation_gain / base.mx : 0.0;
  gain = std::min(gain, std::max(k_room, m_room));
  if (gain < w.min_gain) return base;
  double tau = SlowestFittingReturn(s, base, gain, seat, o, w);
  if (tau == 0) {
    // Even the fastest return cannot hold this gain: the largest that it can.
    double lo = 1, hi = gain;
    for (int it = 0; it < 20; ++it) {
      const double mid = 0.5 * (lo + hi);
      (SlowestFittingReturn(s, base, mid, seat, o, w) > 0 ? lo : hi) = mid;
    }
    gain = lo;
    tau = SlowestFittingReturn(s, base, gain, seat, o, w);
    if (tau == 0 || gain < w.min_gain) return base;
  }
  CinematicScale c = Raised(base, gain, o);
  c.return_tau_s = tau;
  return c;
}

}  // namespace

const CinematicScale& CinematicScaling::ForShot(size_t i) const {
  if (per_shot.empty()) throw Error("", "cinematic scaling has no shots");
  return per_shot[std::min(i, per_shot.size() - 1)];
}

void CinematicOptions::Check() const {
  if (!(reference_depth_u >= 0 && std::isfinite(reference_depth_u))) {
    throw UsageError("reference depth must be >= 0 (0 = automatic)");
  }
  if (!(max_translation_gain > 0 && max_translation_gain <= 100)) {
    throw UsageError("max translation gain must be in (0, 100] m per unit");
  }
  if (!(max_rotation_gain > 0 && max_rotation_gain <= 10)) {
    throw UsageError("max rotation gain must be in (0, 10]");
  }
}

ActuatorFrame CinematicDisplacement(const Eigen::Vector3d& p, double tilt, double pan, double roll,
                                    double zoom_forward_u, const CinematicScale& c,
                                    const SeatGeometry& seat) {
  const Eigen::Vector3d t(c.kx * p.x(), c.ky * p.y(), c.kz * p.z());
  const Eigen::Vector3d f(0, 0, -c.sz * zoom_forward_u);  // zoom-in -> forward (-Z)
  const Eigen::Matrix3d r =
      Rotation(c.mx * tilt, c.my * pan, c.mz * roll) - Eigen::Matrix3d::Identity();
  ActuatorFrame out;
  for (int a = 0; a < kNumActuators; ++a) {
    const Eigen::Vector3d ra = r * seat.FromCenter(a);
    const double nt = t.norm(), nr = ra.norm(), nf = f.norm();
    const double sum = nt + nr + nf;
    out[a] = sum > 0 ? Eigen::Vector3d((nt * t + nr * ra + nf * f) / sum) : Eigen::Vector3d::Zero();
  }
  return out;
}

std::vector<CameraSignals> CinematicShotSignals(const CameraPath& read_path,
                                                const std::vector<ShotRange>& shots,
                                                const CinematicOptions& o,
                                                const WashoutOptions& w) {
  const std::optional<CameraPath> joined = JoinAcrossLostFrames(read_path);
  const CameraPath& path = joined ? *joined : read_path;
  std::vector<CameraSignals> out;
  for (const ShotRange& r : shots) {
    CameraSignals s = ExtractShotSignals(path, r, ShotReferenceDepth(path, r, o.reference_depth_u));
    ApplyConfidenceGain(FrameConfidenceGains(path, r), &s);
    FadeOverLostFrames(path, r, w.cut_ramp_s, &s);
    if (w.HighPass()) {
      std::vector<double> ch(s.size());
      for (int k = 0; k < 3; ++k) {
        for (size_t i = 0; i < s.size(); ++i) ch[i] = s.position_u[i][k];
        HighPassInPlace(s.time_s, &ch, w.tau_s, w.order);
        for (size_t i = 0; i < s.size(); ++i) s.position_u[i][k] = ch[i];
      }
      for (auto* v : {&s.tilt_rad, &s.pan_rad, &s.roll_rad, &s.zoom_forward_u, &s.log_zoom}) {
        HighPassInPlace(s.time_s, v, w.tau_s, w.order);
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

CinematicScaling ComputeCinematicScaling(const CameraPath& path, const SeatGeometry& seat,
                                         const CinematicOptions& o, const WashoutOptions& w) {
  const auto shots = SplitShots(path);
  const auto signals = CinematicShotSignals(path, shots, o, w);
  CinematicScaling scaling;
  for (const auto& s : signals) scaling.per_shot.push_back(BaseScaleForShot(s, seat, o));
  if (o.per_film_scaling && !scaling.per_shot.empty()) {
    // The smallest base factors, then the largest combination gain that
    // every shot allows with them (the gain of one shot may exceed what
    // another, with less cancellation, can take).
    CinematicScale film = scaling.per_shot[0];
    for (const auto& c : scaling.per_shot) {
      film.kx = film.ky = film.kz = film.sz = std::min(film.kx, c.kx);
      film.mx = film.my = film.mz = std::min(film.mx, c.mx);
    }
    double gain = kMaxCombinationGain;
    for (const auto& s : signals) gain = std::min(gain, CombinationGain(s, seat, o, film));
    for (auto& c : scaling.per_shot) c = Scaled(film, gain);
  } else {
    for (size_t i = 0; i < signals.size(); ++i) {
      scaling.per_shot[i] =
          Scaled(scaling.per_shot[i], CombinationGain(signals[i], seat, o, scaling.per_shot[i]));
      if (w.mode == WashoutMode::kAdaptive) {
        scaling.per_shot[i] = AdaptiveReturnForShot(signals[i], seat, o, w, scaling.per_shot[i]);
      }
    }
  }
  // A shot of mostly low confidence is felt weakly: scaling must not blow
  // its confidence-weighted motion back up to the full range.
  const std::vector<double> qualities = ShotQualityGains(path, shots);
  for (size_t i = 0; i < shots.size(); ++i) {
    const double quality = qualities[i];
    if (quality < 1) scaling.per_shot[i] = Scaled(scaling.per_shot[i], quality);
  }
  return scaling;
}

std::vector<ActuatorFrame> CinematicFrames(const CameraPath& path, const SeatGeometry& seat,
                                           const CinematicOptions& o, const WashoutOptions& w,
                                           const CinematicScaling& scaling) {
  const auto shots = SplitShots(path);
  const auto signals = CinematicShotSignals(path, shots, o, w);
  std::vector<ActuatorFrame> out;
  out.reserve(path.frames.size());
  for (size_t k = 0; k < shots.size(); ++k) {
    const CinematicScale& c = scaling.ForShot(k);
    const double tau = w.mode == WashoutMode::kAdaptive ? c.return_tau_s : 0.0;
    const std::vector<ActuatorFrame> f =
        Returned(signals[k], ShotFrames(signals[k], c, seat), tau, w);
    out.insert(out.end(), f.begin(), f.end());
  }
  return out;
}

}  // namespace hapcine
