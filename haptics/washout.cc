#include "haptics/washout.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace hapcine {

void WashoutOptions::Check() const {
  if (!(tau_s > 0.05 && tau_s <= 600)) throw UsageError("washout tau_s must be in (0.05, 600]");
  if (order != 1 && order != 2) throw UsageError("washout order must be 1 or 2");
  if (!(cut_ramp_s >= 0 && cut_ramp_s <= 10)) throw UsageError("cut_ramp_s must be in [0, 10]");
  if (!(max_speed_m_s > 0 && max_speed_m_s <= 10)) {
    throw UsageError("max_speed_m_s must be in (0, 10]");
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

void ApplyCutTransitions(const std::vector<double>& t, const std::vector<double>& cuts,
                         double ramp_s, std::vector<ActuatorFrame>* frames) {
  if (ramp_s <= 0) return;
  auto& v = *frames;
  for (double c : cuts) {
    auto it = std::lower_bound(t.begin(), t.end(), c);
    if (it == t.begin() || it == t.end()) continue;
    size_t i = static_cast<size_t>(it - t.begin());
    const ActuatorFrame held = v[i - 1];
    for (; i < t.size() && t[i] < c + ramp_s; ++i) {
      const double w = SmootherStep((t[i] - c) / ramp_s);
      for (int a = 0; a < kNumActuators; ++a) v[i][a] = (1 - w) * held[a] + w * v[i][a];
    }
  }
}

int LimitVelocity(double max_step_m, std::vector<ActuatorFrame>* frames) {
  auto& v = *frames;
  int limited = 0;
  for (size_t i = 1; i < v.size(); ++i) {
    bool hit = false;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        const double d = v[i][a][k] - v[i - 1][a][k];
        if (std::abs(d) > max_step_m) {
          v[i][a][k] = v[i - 1][a][k] + std::copysign(max_step_m, d);
          hit = true;
        }
      }
    }
    limited += hit;
  }
  return limited;
}

int ClampToWorkspace(double clamp_half_m, std::vector<ActuatorFrame>* frames) {
  int clamped = 0;
  for (auto& f : *frames) {
    bool hit = false;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        double& c = f[a][k];
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

}  // namespace hapcine
