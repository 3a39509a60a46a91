#include "haptics/semantic_model.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

struct Names {
  CameraEffect effect;
  const char* table1;
  const char* table2;
};
const Names kNames[] = {
    {CameraEffect::kNone, "none", "none"},
    {CameraEffect::kCraneShot, "crane_shot", "flying_away"},
    {CameraEffect::kDutchAngle, "dutch_angle", "instability"},
    {CameraEffect::kArcing, "arcing", "intensification"},
    {CameraEffect::kTraveling, "traveling", "crab_walk"},
    {CameraEffect::kTilting, "tilting", "inferiority"},
    {CameraEffect::kZoomIn, "zoom_in", "walk_forward"},
    {CameraEffect::kVertigo, "vertigo", "vertigo"},
};

bool IsLinear(CameraEffect e) {
  return e == CameraEffect::kArcing || e == CameraEffect::kTilting || e == CameraEffect::kVertigo;
}

// Whole number of cycles closest to duration / cycle_s (at least one).
// The crab walk's two hands at progress u in [0, 1] of a segment of
// duration_s, each in [0, 1]: strokes out and back, each 2 half-steps long
// ((1 - cos(2 pi v)) / 2, zero velocity at both ends), the hands taking
// turns one half-step apart, so one hand returns while the other moves out.
// A whole number of half-steps (>= 2) of about cycle_s / 2; the first
// half-step moves the leading hand alone and the last returns the last hand
// alone, so the pattern starts and ends at the centre.
void CrabWalkSteps(double duration_s, double cycle_s, double u, double* lead, double* trail) {
  const int half_steps = std::max(2, static_cast<int>(std::lround(2 * duration_s / cycle_s)));
  const double tau = u * half_steps;  // in half-steps
  *lead = *trail = 0;
  for (int k = static_cast<int>(std::floor(tau)) - 1; k <= static_cast<int>(std::floor(tau)); ++k) {
    if (k < 0 || k > half_steps - 2) continue;
    const double v = (tau - k) / 2;
    if (v < 0 || v > 1) continue;
    (k % 2 == 0 ? *lead : *trail) += (1 - std::cos(2 * kPi * v)) / 2;
  }
}

int Cycles(double duration_s, double cycle_s) {
  return std::max(1, static_cast<int>(std::lround(duration_s / cycle_s)));
}

// Unit vector from a to b per coordinate-bounded use (|each coord| <= 1).
Eigen::Vector3d Unit(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

}  // namespace

const char* EffectName(CameraEffect e) { return kNames[static_cast<int>(e)].table1; }
const char* MetaphorName(CameraEffect e) { return kNames[static_cast<int>(e)].table2; }

std::optional<CameraEffect> EffectFromName(const std::string& name) {
  for (const auto& n : kNames) {
    if (name == n.table1 || name == n.table2) return n.effect;
  }
  return std::nullopt;
}

void SemanticOptions::Check() const {
  if (!(cycle_s >= 0.2 && cycle_s <= 30)) throw UsageError("semantic cycle_s must be in [0.2, 30]");
  if (!(release_s >= 0 && release_s <= 30))
    throw UsageError("semantic release_s must be in [0, 30]");
}

void CheckSegments(const std::vector<EffectSegment>& segs) {
  for (size_t i = 0; i < segs.size(); ++i) {
    const auto& s = segs[i];
    if (!(std::isfinite(s.start_s) && std::isfinite(s.end_s) && s.start_s < s.end_s)) {
      throw UsageError("effect segment " + std::to_string(i) + ": need start_s < end_s");
    }
    if (!(std::abs(s.intensity) <= 1)) {
      throw UsageError("effect segment " + std::to_string(i) + ": intensity outside [-1, 1]");
    }
    if (i > 0 && s.start_s < segs[i - 1].end_s) {
      throw UsageError("effect segment " + std::to_string(i) + " overlaps the previous one");
    }
  }
}

ActuatorFrame SemanticPattern(const EffectSegment& seg, double t, const SeatGeometry& seat,
                              const SemanticOptions& o) {
  ActuatorFrame out;
  for (auto& v : out) v.setZero();
  if (t < seg.start_s) return out;
  const double dur = seg.end_s - seg.start_s;
  const double u = std::min(1.0, (t - seg.start_s) / dur);
  const double amp = std::abs(seg.intensity) * seat.usable_half_m;
  const double sgn = seg.intensity < 0 ? -1.0 : 1.0;
  const int n = Cycles(dur, o.cycle_s);
  const double phase = 2 * kPi * n * u;
  constexpr int H = 0, L = 1, R = 2;
  switch (seg.effect) {
    case CameraEffect::kNone:
      break;
    case CameraEffect::kCraneShot: {  // flying away: up/down, growing
      const double y = sgn * amp * u * std::sin(phase);
      for (auto& v : out) v.y() = y;
      break;
    }
    case CameraEffect::kDutchAngle: {  // instability: boat sway
      const double s = sgn * amp * std::sin(phase);
      out[L].y() = s;
      out[R].y() = -s;
      out[H].x() = -0.5 * s;
      break;
    }
    case CameraEffect::kArcing:  // intensification: towards G
      for (int a = 0; a < kNumActuators; ++a) out[a] = sgn * amp * u * Unit(-seat.FromCenter(a));
      break;
    case CameraEffect::kVertigo:  // away from G
      for (int a = 0; a < kNumActuators; ++a) out[a] = sgn * amp * u * Unit(seat.FromCenter(a));
      break;
    case CameraEffect::kTilting:  // inferiority: all down
      for (auto& v : out) v.y() = -sgn * amp * u;
      break;
    case CameraEffect::kTraveling:
    case CameraEffect::kZoomIn: {
      // Crab walk (Table 2): the leading hand (right when moving right)
      // steps out; then it goes back while the other hand steps out; and so on.
      double lead = 0, trail = 0;
      CrabWalkSteps(dur, o.cycle_s, u, &lead, &trail);
      lead *= amp;
      trail *= amp;
      const int axis = seg.effect == CameraEffect::kTraveling ? 0 : 2;
      const double dir = seg.effect == CameraEffect::kTraveling ? sgn : -sgn;  // forward = -Z
      const int lead_hand = sgn > 0 ? R : L;
      const int trail_hand = sgn > 0 ? L : R;
      out[lead_hand][axis] = dir * lead;
      out[trail_hand][axis] = dir * trail;
      out[H][axis] = dir * 0.3 * (lead + trail);
      break;
    }
  }
  return out;
}

std::vector<ActuatorFrame> SemanticFrames(const std::vector<double>& time_s,
                                          const std::vector<EffectSegment>& segs,
                                          const SeatGeometry& seat, const SemanticOptions& o,
                                          std::vector<CameraEffect>* effect_at) {
  CheckSegments(segs);
  std::vector<ActuatorFrame> out(time_s.size());
  for (auto& f : out)
    for (auto& v : f) v.setZero();
  if (effect_at) effect_at->assign(time_s.size(), CameraEffect::kNone);
  for (size_t k = 0; k < segs.size(); ++k) {
    const EffectSegment& s = segs[k];
    const double next_start = k + 1 < segs.size() ? segs[k + 1].start_s : 1e300;
    const double release = IsLinear(s.effect) ? std::min(o.release_s, next_start - s.end_s) : 0.0;
    const ActuatorFrame held = SemanticPattern(s, s.end_s, seat, o);
    auto first = std::lower_bound(time_s.begin(), time_s.end(), s.start_s);
    for (size_t i = static_cast<size_t>(first - time_s.begin()); i < time_s.size(); ++i) {
      const double t = time_s[i];
      if (t <= s.end_s) {
        out[i] = SemanticPattern(s, t, seat, o);
        if (effect_at) (*effect_at)[i] = s.effect;
      } else if (t < s.end_s + release) {
        const double w = 1 - SmootherStep((t - s.end_s) / release);
        for (int a = 0; a < kNumActuators; ++a) out[i][a] = w * held[a];
      } else {
        break;
      }
    }
  }
  return out;
}

}  // namespace hapcine
