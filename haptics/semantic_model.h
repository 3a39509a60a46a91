#pragma once
// The Semantic model (section 4.4, Table 2): instead of the camera's
// movement, the user feels a metaphor of the camera effect's purpose. Each
// effect segment [start_s, end_s] becomes a pattern of the three actuators;
// intensity in [-1, 1] scales it to |intensity| * usable_half_m and its sign
// mirrors the direction (e.g. a crab walk to the left, a zoom-out).
//
//   effect (Table 1)  metaphor          pattern (u = (t - start) / duration)
//   crane_shot        flying_away       all actuators up and down, n cycles,
//                                       amplitude growing linearly with u
//   dutch_angle       instability       left hand up while right goes down and
//                                       vice versa, head sways sideways (boat)
//   arcing            intensification   linear: all actuators towards G
//   traveling         crab_walk         right hand steps right; then it comes
//                                       back while the left steps right; then
//                                       the left comes back while the right
//                                       steps, and so on
//   tilting           inferiority       linear: all actuators down
//   zoom_in           walk_forward      the crab walk along -Z (forward)
//   vertigo           vertigo           linear: all actuators away from G
// Dynamic patterns (crane, dutch) use a whole number of cycles of period
// ~cycle_s; the crab walk and walk forward a whole number of half-steps of
// ~cycle_s / 2 (each hand's stroke out and back lasts cycle_s). All start
// and end at the centre with zero velocity. Linear patterns hold their end value after end_s and return to
// the centre over release_s (shortened if the next segment starts sooner).

#include <optional>
#include <string>
#include <vector>

#include "haptics/seat_geometry.h"
#include "haptics/washout.h"

namespace hapcine {

enum class CameraEffect {
  kNone = 0,
  kCraneShot,
  kDutchAngle,
  kArcing,
  kTraveling,
  kTilting,
  kZoomIn,
  kVertigo,
};
constexpr int kNumCameraEffects = 8;

const char* EffectName(CameraEffect e);    // "none", "crane_shot", ... (Table 1)
const char* MetaphorName(CameraEffect e);  // "none", "flying_away", ... (Table 2)
// Accepts either name; nullopt when unknown.
std::optional<CameraEffect> EffectFromName(const std::string& name);

struct EffectSegment {
  double start_s = 0;
  double end_s = 0;
  CameraEffect effect = CameraEffect::kNone;
  double intensity = 1.0;  // [-1, 1]
};

struct SemanticOptions {
  double cycle_s = 1.0;    // period of the dynamic patterns
  double release_s = 1.0;  // return to the centre after a linear pattern
  void Check() const;      // throws UsageError
};

// Pattern of one segment at time t (zero before start_s; the linear
// patterns' held value after end_s, without the release).
ActuatorFrame SemanticPattern(const EffectSegment& segment, double t_s, const SeatGeometry& seat,
                              const SemanticOptions& options);

// Throws UsageError unless segments are sorted, non-overlapping, finite,
// start < end and |intensity| <= 1.
void CheckSegments(const std::vector<EffectSegment>& segments);

// The track for sample times time_s; `effect_at` (optional) receives the
// effect active at each sample (kNone between segments).
std::vector<ActuatorFrame> SemanticFrames(const std::vector<double>& time_s,
                                          const std::vector<EffectSegment>& segments,
                                          const SeatGeometry& seat, const SemanticOptions& options,
                                          std::vector<CameraEffect>* effect_at = nullptr);

}  // namespace hapcine
