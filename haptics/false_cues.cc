#include "haptics/false_cues.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "haptics/camera_signals.h"

namespace hapcine {
namespace {

// A speed below this is still whatever the shot does (0.1 mm/s).
constexpr double kStillFloorMS = 1e-4;

struct Retreat {
  double counter_m = 0, duration_s = 0, at_s = 0;
};

// Largest retreat of sign * coordinate over the track samples in [t0, t1]:
// the running peak minus the current value (a drawdown).
Retreat LargestRetreat(const HapticTrack& track, double t0, double t1, int a, int k, int sign) {
  Retreat worst;
  auto it = std::lower_bound(track.samples.begin(), track.samples.end(), t0,
                             [](const HapticSample& s, double t) { return s.time_s < t; });
  double best = -INFINITY, best_t = t0;
  for (; it != track.samples.end() && it->time_s <= t1; ++it) {
    const double v = sign * it->pos_m[a][k];
    if (v > best) {
      best = v;
      best_t = it->time_s;
    } else if (best - v > worst.counter_m) {
      worst = {best - v, it->time_s - best_t, best_t};
    }
  }
  return worst;
}

double PeakReferenceSpeed(const CameraPath& path, const ShotRange& r,
                          const std::vector<ActuatorFrame>& ref) {
  double peak = 0;
  for (size_t i = r.first + 1; i <= r.last; ++i) {
    const double dt = path.frames[i].time_s - path.frames[i - 1].time_s;
    for (int a = 0; a < kNumActuators; ++a) {
      peak = std::max(peak, (ref[i][a] - ref[i - 1][a]).cwiseAbs().maxCoeff() / dt);
    }
  }
  return peak;
}

// The worst retreat of one coordinate over the runs where its reference
// keeps moving one way; returns it into `cue` when larger.
void MeasureCoordinate(const CameraPath& path, const HapticTrack& track, const ShotRange& r,
                       const std::vector<ActuatorFrame>& ref, double still_speed, double from_s,
                       int a, int k, ShotFalseCue* cue) {
  auto sign_at = [&](size_t i) {
    const double dt = path.frames[i].time_s - path.frames[i - 1].time_s;
    const double d = ref[i][a][k] - ref[i - 1][a][k];
    return std::abs(d) / dt > still_speed ? (d > 0 ? 1 : -1) : 0;
  };
  size_t i = r.first + 1;
  while (i <= r.last) {
    const int sign = sign_at(i);
    size_t j = i;
    while (j + 1 <= r.last && sign_at(j + 1) == sign) ++j;
    if (sign != 0) {
      const double t0 = std::max(path.frames[i - 1].time_s, from_s);
      const Retreat w = LargestRetreat(track, t0, path.frames[j].time_s, a, k, sign);
      if (w.counter_m > cue->counter_m) {
        cue->counter_m = w.counter_m;
        cue->duration_s = w.duration_s;
        cue->at_s = w.at_s;
        cue->actuator = a;
        cue->axis = k;
      }
    }
    i = j + 1;
  }
}

double TrackPeakIn(const HapticTrack& track, double t0, double t1) {
  double peak = 0;
  for (const HapticSample& s : track.samples) {
    if (s.time_s < t0 || s.time_s > t1) continue;
    for (int a = 0; a < kNumActuators; ++a) peak = std::max(peak, s.pos_m[a].cwiseAbs().maxCoeff());
  }
  return peak;
}

}  // namespace

std::vector<ShotFalseCue> MeasureFalseCues(const CameraPath& path, const HapticTrack& track,
                                           const SeatGeometry& seat,
                                           const CinematicOptions& cinematic,
                                           const FalseCueOptions& o) {
  WashoutOptions plain;
  plain.mode = WashoutMode::kOff;
  const CinematicScaling scaling = ComputeCinematicScaling(path, seat, cinematic, plain);
  const std::vector<ActuatorFrame> ref = CinematicFrames(path, seat, cinematic, plain, scaling);
  const std::vector<ShotRange> shots = SplitShots(path);
  std::vector<ShotFalseCue> out;
  for (size_t n = 0; n < shots.size(); ++n) {
    const ShotRange& r = shots[n];
    ShotFalseCue cue;
    cue.shot = r.shot;
    cue.start_s = path.frames[r.first].time_s;
    cue.end_s = path.frames[r.last].time_s;
    const double still_speed =
        std::max(kStillFloorMS, o.still_fraction * PeakReferenceSpeed(path, r, ref));
    const double from_s = cue.start_s + (n > 0 ? o.cut_ramp_s : 0.0);
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) MeasureCoordinate(path, track, r, ref, still_speed, from_s, a, k, &cue);
    }
    cue.peak_m = TrackPeakIn(track, from_s, cue.end_s);
    out.push_back(cue);
  }
  return out;
}

nlohmann::json FalseCuesToJson(const std::vector<ShotFalseCue>& cues) {
  nlohmann::json shots = nlohmann::json::array();
  double worst = 0;
  for (const ShotFalseCue& c : cues) {
    worst = std::max(worst, c.counter_m);
    shots.push_back({{"shot", c.shot},
                     {"start_s", c.start_s},
                     {"end_s", c.end_s},
                     {"counter_motion_m", c.counter_m},
                     {"duration_s", c.duration_s},
                     {"at_s", c.at_s},
                     {"actuator", ActuatorName(static_cast<Actuator>(c.actuator))},
                     {"axis", std::string(1, "xyz"[c.axis])},
                     {"peak_m", c.peak_m}});
  }
  return {{"shots", shots}, {"max_counter_motion_m", worst}};
}

std::string FormatFalseCueTable(const std::vector<ShotFalseCue>& cues) {
  std::ostringstream out;
  out << "false cues (counter-motion while the camera keeps its direction)\n";
  out << "shot    start_s    end_s  counter_mm  duration_s     at_s  where    peak_mm\n";
  out << std::fixed;
  double worst = 0;
  for (const ShotFalseCue& c : cues) {
    worst = std::max(worst, c.counter_m);
    const std::string where = c.counter_m > 0 ? std::string(ActuatorName(static_cast<Actuator>(
                                                    c.actuator))) + "." + "xyz"[c.axis]
                                              : "-";
    out << std::setw(4) << c.shot << std::setprecision(2) << std::setw(11) << c.start_s
        << std::setw(9) << c.end_s << std::setprecision(1) << std::setw(12) << c.counter_m * 1e3
        << std::setprecision(2) << std::setw(12) << c.duration_s << std::setw(9) << c.at_s
        << "  " << std::left << std::setw(8) << where << std::right << std::setprecision(1)
        << std::setw(8) << c.peak_m * 1e3 << "\n";
  }
  out << "largest counter-motion " << std::setprecision(1) << worst * 1e3 << " mm over "
      << cues.size() << " shot(s); more than 1 mm: "
      << std::count_if(cues.begin(), cues.end(),
                       [](const ShotFalseCue& c) { return c.counter_m > 1e-3; })
      << "\n";
  return out.str();
}

}  // namespace hapcine
