#include "haptics/washout.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace hapcine {

const char* WashoutModeName(WashoutMode m) {
  switch (m) {
    case WashoutMode::kOff:
      return "off";
    case WashoutMode::kHighPass:
      return "highpass";
    case WashoutMode::kAdaptive:
      return "adaptive";
  }
  return "?";
}

WashoutMode WashoutModeFromName(const std::string& name) {
  for (WashoutMode m : {WashoutMode::kOff, WashoutMode::kHighPass, WashoutMode::kAdaptive}) {
    if (name == WashoutModeName(m)) return m;
  }
  throw UsageError("unknown washout '" + name + "' (expected adaptive, highpass or off)");
}

void WashoutOptions::Check() const {
  if (!(tau_s > 0.05 && tau_s <= 600)) throw UsageError("washout tau_s must be in (0.05, 600]");
  if (order != 1 && order != 2) throw UsageError("washout order must be 1 or 2");
  if (!(cut_ramp_s >= 0 && cut_ramp_s <= 10)) throw UsageError("cut_ramp_s must be in [0, 10]");
  if (!(max_speed_m_s > 0 && max_speed_m_s <= 10)) {
    throw UsageError("max_speed_m_s must be in (0, 10]");
  }
  if (!(window_s > 0 && window_s <= 3600)) throw UsageError("window_s must be in (0, 3600]");
  if (!(min_gain >= 1 && min_gain <= 100)) throw UsageError("min_gain must be in [1, 100]");
  if (!(return_accel_m_s2 > 0 && return_accel_m_s2 <= 100)) {
    throw UsageError("return_accel_m_s2 must be in (0, 100]");
  }
  if (!(still_fraction >= 0 && still_fraction < 1)) {
    throw UsageError("still_fraction must be in [0, 1)");
  }
}

// A coordinate slower than this is still whatever the shot does (0.1 mm/s).
constexpr double kStillFloorMS = 1e-4;

double StillSpeed(const std::vector<double>& t, const std::vector<ActuatorFrame>& f,
                  double still_fraction) {
  double peak = 0;
  for (size_t i = 1; i < f.size(); ++i) {
    const double dt = t[i] - t[i - 1];
    for (int a = 0; a < kNumActuators; ++a) {
      peak = std::max(peak, (f[i][a] - f[i - 1][a]).cwiseAbs().maxCoeff() / dt);
    }
  }
  return std::max(kStillFloorMS, still_fraction * peak);
}

double PeakCoordinate(const std::vector<ActuatorFrame>& f) {
  double peak = 0;
  for (const ActuatorFrame& v : f) {
    for (const auto& p : v) peak = std::max(peak, p.cwiseAbs().maxCoeff());
  }
  return peak;
}

double LargestWindowRange(const std::vector<double>& t, const std::vector<ActuatorFrame>& f,
                          double window_s) {
  double largest = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    ActuatorFrame lo = f[i], hi = f[i];
    for (size_t j = i + 1; j < f.size() && t[j] - t[i] <= window_s; ++j) {
      for (int a = 0; a < kNumActuators; ++a) {
        lo[a] = lo[a].cwiseMin(f[j][a]);
        hi[a] = hi[a].cwiseMax(f[j][a]);
      }
    }
    for (int a = 0; a < kNumActuators; ++a) largest = std::max(largest, (hi[a] - lo[a]).maxCoeff());
  }
  return largest;
}

void ApplyReturnToCentre(const std::vector<double>& t, double still_speed, double tau_s,
                         double accel_m_s2, std::vector<ActuatorFrame>* frames) {
  auto& f = *frames;
  if (f.empty()) return;
  ActuatorFrame prev_in = f[0];
  ActuatorFrame ret;  // return speed per coordinate, m/s, towards -sign(p)
  for (auto& r : ret) r.setZero();
  for (size_t i = 1; i < f.size(); ++i) {
    const double dt = t[i] - t[i - 1];
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        const double in_speed = (f[i][a][k] - prev_in[a][k]) / dt;
        const double out_prev = f[i - 1][a][k];
        double& r = ret[a][k];
        const double step = accel_m_s2 * dt;
        r += std::clamp(out_prev / tau_s - r, -step, step);
        // Never against a moving coordinate: at most cancel its motion.
        if (in_speed > still_speed) r = std::min(r, in_speed);
        if (in_speed < -still_speed) r = std::max(r, in_speed);
        prev_in[a][k] = f[i][a][k];
        f[i][a][k] = out_prev + (in_speed - r) * dt;
      }
    }
  }
}

void HighPassInPlace(const std::vector<double>& t, std::vector<double>* x, double tau_s,
                     int order) {
  for (int pass = 0; pass < order; ++pass) {
    std::vector<double>& v = *x;
    if (v.empty()) return;
    double prev_in = v[0];
    double prev_out = 0;
    v[0] = 0;
    for (size_t i = 1; i < v.size(); ++i) {
      const double dt = t[i] - t[i - 1];
      const double a = tau_s / (tau_s + dt);
      const double in = v[i];
      const double out = a * (prev_out + in - prev_in);
      prev_in = in;
      prev_out = out;
      v[i] = out;
    }
  }
}

double SmootherStep(double u) {
  if (!(u > 0)) return 0;
  if (u >= 1) return 1;
  return u * u * u * (u * (u * 6 - 15) + 10);
}

namespace {

// The three actuator positions of one output sample: the same steps shape a
// model's frames and a haptic track's samples (built in place for long films).
Eigen::Vector3d* Positions(ActuatorFrame& f) { return f.data(); }
Eigen::Vector3d* Positions(HapticSample& s) { return s.pos_m; }

template <class Frame>
void ApplyCutTransitionsTo(const std::vector<double>& t, const std::vector<double>& cuts,
                           double ramp_s, std::vector<Frame>* frames) {
  if (ramp_s <= 0) return;
  auto& v = *frames;
  for (double c : cuts) {
    auto it = std::lower_bound(t.begin(), t.end(), c);
    if (it == t.begin() || it == t.end()) continue;
    size_t i = static_cast<size_t>(it - t.begin());
    ActuatorFrame held;
    std::copy_n(Positions(v[i - 1]), kNumActuators, held.begin());
    for (; i < t.size() && t[i] < c + ramp_s; ++i) {
      const double w = SmootherStep((t[i] - c) / ramp_s);
      Eigen::Vector3d* p = Positions(v[i]);
      for (int a = 0; a < kNumActuators; ++a) p[a] = (1 - w) * held[a] + w * p[a];
    }
  }
}

template <class Frame>
int LimitVelocityOf(double max_step_m, std::vector<Frame>* frames) {
  auto& v = *frames;
  int limited = 0;
  for (size_t i = 1; i < v.size(); ++i) {
    const Eigen::Vector3d* prev = Positions(v[i - 1]);
    Eigen::Vector3d* p = Positions(v[i]);
    bool hit = false;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        const double d = p[a][k] - prev[a][k];
        if (std::abs(d) > max_step_m) {
          p[a][k] = prev[a][k] + std::copysign(max_step_m, d);
          hit = true;
        }
      }
    }
    limited += hit;
  }
  return limited;
}

template <class Frame>
int ClampToWorkspaceOf(double clamp_half_m, std::vector<Frame>* frames) {
  int clamped = 0;
  for (auto& f : *frames) {
    Eigen::Vector3d* p = Positions(f);
    bool hit = false;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        double& c = p[a][k];
        if (!std::isfinite(c)) {
          c = 0;  // never reaches a device; counted as clamped
          hit = true;
        } else if (std::abs(c) > clamp_half_m) {
          c = std::copysign(clamp_half_m, c);
          hit = true;
        }
      }
    }
    clamped += hit;
  }
  return clamped;
}

}  // namespace

void ApplyCutTransitions(const std::vector<double>& t, const std::vector<double>& cuts,
                         double ramp_s, std::vector<ActuatorFrame>* frames) {
  ApplyCutTransitionsTo(t, cuts, ramp_s, frames);
}
void ApplyCutTransitions(const std::vector<double>& t, const std::vector<double>& cuts,
                         double ramp_s, std::vector<HapticSample>* samples) {
  ApplyCutTransitionsTo(t, cuts, ramp_s, samples);
}

int LimitVelocity(double max_step_m, std::vector<ActuatorFrame>* frames) {
  return LimitVelocityOf(max_step_m, frames);
}
int LimitVelocity(double max_step_m, std::vector<HapticSample>* samples) {
  return LimitVelocityOf(max_step_m, samples);
}

int LimitSpeed(double max_speed_m_s, double rate_hz, std::vector<HapticSample>* samples,
               std::vector<char>* limited_rows) {
  auto& v = *samples;
  if (limited_rows) limited_rows->assign(v.size(), 0);
  const double regular_step = max_speed_m_s / rate_hz;
  int limited = 0;
  for (size_t i = 1; i < v.size(); ++i) {
    const double dt = v[i].time_s - v[i - 1].time_s;
    // Rows at the stored rate take the very step LimitVelocity does.
    const double max_step =
        std::abs(dt * rate_hz - 1) < 1e-6 ? regular_step : max_speed_m_s * dt;
    bool hit = false;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        const double d = v[i].pos_m[a][k] - v[i - 1].pos_m[a][k];
        if (std::abs(d) > max_step) {
          v[i].pos_m[a][k] = v[i - 1].pos_m[a][k] + std::copysign(max_step, d);
          hit = true;
        }
      }
    }
    limited += hit;
    if (limited_rows) (*limited_rows)[i] = hit;
  }
  return limited;
}

int ClampToWorkspace(double clamp_half_m, std::vector<ActuatorFrame>* frames) {
  return ClampToWorkspaceOf(clamp_half_m, frames);
}
int ClampToWorkspace(double clamp_half_m, std::vector<HapticSample>* samples) {
  return ClampToWorkspaceOf(clamp_half_m, samples);
}

}  // namespace hapcine
