// Tracking error of the simulated seat (haptics/sim_device.h: a Falcon with a
// relaxed hand on it) under Equation 7's spring-damper, over a grid of k and
// d: where the player's defaults (k = 300 N/m, d = 2 N s/m) come from
// (docs/player.md, "Where k and d come from"). For every track and (k, d),
// SimulateSeat plays the track offline through the safety layer; the error
// is |grip - target| per actuator at 100 Hz over the track's time span.
//
//   build/player/hapcine_seat_tracking_bench A.haptic.csv [B.haptic.csv ...]
//       [--k 100,200,300,500,800] [--d 0.5,1,2,4,8]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/haptic_track.h"
#include "player/simulate_seat.h"

namespace {

std::vector<double> ParseList(const char* s) {
  std::vector<double> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}

struct TrackingError {
  double sum_sq = 0, max = 0;
  size_t n = 0;
};

// |grip - target| over the target's time span, every actuator.
void AddError(const hapcine::HapticTrack& target, const hapcine::HapticTrack& grip,
              TrackingError* e) {
  using hapcine::kNumActuators;
  Eigen::Vector3d p[kNumActuators];
  size_t hint = 0;
  for (const hapcine::HapticSample& s : grip.samples) {
    if (s.time_s > target.samples.back().time_s) break;
    target.Sample(s.time_s, p, &hint);
    for (int a = 0; a < kNumActuators; ++a) {
      const double err = (s.pos_m[a] - p[a]).norm();
      e->sum_sq += err * err;
      e->max = std::max(e->max, err);
      ++e->n;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hapcine;
  std::vector<double> ks = {100, 200, 300, 500, 800}, ds = {0.5, 1, 2, 4, 8};
  std::vector<HapticTrack> tracks;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--k") == 0 && i + 1 < argc) {
      ks = ParseList(argv[++i]);
    } else if (std::strcmp(argv[i], "--d") == 0 && i + 1 < argc) {
      ds = ParseList(argv[++i]);
    } else if (argv[i][0] == '-') {
      std::printf("usage: %s TRACK.haptic.csv... [--k LIST] [--d LIST]\n", argv[0]);
      return std::strcmp(argv[i], "--help") == 0 ? 0 : 2;
    } else {
      tracks.push_back(ReadHapticTrackFile(argv[i]));
    }
  }
  if (tracks.empty()) {
    std::fprintf(stderr, "no track given\n");
    return 2;
  }
  std::printf("k_n_m,d_n_s_m,rms_mm,max_mm\n");
  for (double k : ks) {
    for (double d : ds) {
      LoopOptions loop;
      loop.k_n_m = k;
      loop.d_n_s_m = d;
      TrackingError e;
      for (const HapticTrack& t : tracks) AddError(t, SimulateSeat(t, loop), &e);
      std::printf("%g,%g,%.3f,%.3f\n", k, d, 1e3 * std::sqrt(e.sum_sq / std::max<size_t>(1, e.n)),
                  1e3 * e.max);
      std::fflush(stdout);
    }
  }
  return 0;
}
