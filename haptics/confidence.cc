#include "haptics/confidence.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "core/shot_quality_header.h"
#include "haptics/washout.h"

namespace hapcine {
namespace {

double FrameConfidence(const CameraFrame& f) {
  if (IsLost(f)) return 0;
  return f.confidence ? *f.confidence : 1.0;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 1;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

// The shots whose `shot_quality.<shot>` header line says doubtful:1 (docs/formats.md).
std::set<int> DoubtfulInHeader(const CameraPath& path) {
  std::set<int> doubtful;
  for (const ShotQuality& q : ReadShotQuality(path))
    if (q.doubtful) doubtful.insert(q.shot);
  return doubtful;
}

}  // namespace

double ConfidenceGain(double confidence) { return SmootherStep(confidence / kFullGainConfidence); }

std::vector<double> FrameConfidenceGains(const CameraPath& path, const ShotRange& r) {
  const size_t n = r.last - r.first + 1;
  std::vector<double> gains(n);
  // Window average with two pointers (the window moves forward with i).
  size_t lo = r.first, hi = r.first;
  double sum = 0;
  for (size_t i = r.first; i <= r.last; ++i) {
    const double t = path.frames[i].time_s;
    while (hi <= r.last && path.frames[hi].time_s <= t + kConfidenceWindowS / 2) {
      sum += FrameConfidence(path.frames[hi++]);
    }
    while (path.frames[lo].time_s < t - kConfidenceWindowS / 2) {
      sum -= FrameConfidence(path.frames[lo++]);
    }
    gains[i - r.first] = ConfidenceGain(sum / static_cast<double>(hi - lo));
  }
  return gains;
}

void ApplyConfidenceGain(const std::vector<double>& g, CameraSignals* s) {
  if (std::all_of(g.begin(), g.end(), [](double v) { return v == 1.0; })) return;
  auto gain_changes = [&](std::vector<double>* x) {
    double prev_in = (*x)[0];
    for (size_t i = 1; i < x->size(); ++i) {
      const double in = (*x)[i];
      (*x)[i] = (*x)[i - 1] + g[i] * (in - prev_in);
      prev_in = in;
    }
  };
  for (auto* v : {&s->tilt_rad, &s->pan_rad, &s->roll_rad, &s->zoom_forward_u, &s->log_zoom}) {
    gain_changes(v);
  }
  std::vector<double> ch(s->size());
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < s->size(); ++i) ch[i] = s->position_u[i][k];
    gain_changes(&ch);
    for (size_t i = 0; i < s->size(); ++i) s->position_u[i][k] = ch[i];
  }
}

double ShotQualityGain(const std::vector<double>& gains, bool doubtful) {
  const double g = Median(gains);
  return doubtful ? std::min(g, ConfidenceGain(kLowMedianConfidence)) : g;
}

std::vector<double> ShotQualityGains(const CameraPath& path, const std::vector<ShotRange>& shots) {
  const std::set<int> doubtful = DoubtfulInHeader(path);
  std::vector<double> gains;
  for (const ShotRange& r : shots)
    gains.push_back(ShotQualityGain(FrameConfidenceGains(path, r), doubtful.count(r.shot) > 0));
  return gains;
}

std::vector<ShotConfidence> AssessShotConfidence(const CameraPath& path,
                                                 const std::vector<ShotRange>& shots) {
  std::vector<ShotConfidence> out;
  const std::set<int> doubtful_in_header = DoubtfulInHeader(path);
  for (const ShotRange& r : shots) {
    ShotConfidence c;
    c.shot = r.shot;
    c.start_s = path.frames[r.first].time_s;
    c.end_s = path.frames[r.last].time_s;
    c.frames = r.last - r.first + 1;
    std::vector<double> conf;
    for (size_t i = r.first; i <= r.last; ++i) {
      conf.push_back(FrameConfidence(path.frames[i]));
      c.lost += IsLost(path.frames[i]);
    }
    c.median_confidence = Median(conf);
    c.header_doubtful = doubtful_in_header.count(r.shot) > 0;
    c.gain = ShotQualityGain(FrameConfidenceGains(path, r), c.header_doubtful);
    c.low = c.header_doubtful || c.lost > kLowLostShare * c.frames ||
            c.median_confidence < kLowMedianConfidence;
    out.push_back(c);
  }
  return out;
}

std::string LowQualityShotLine(const ShotConfidence& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "shot %d (%.2f-%.2f s): low quality (median confidence %.2f, %zu of %zu frames "
                "lost%s): haptic gain %.2f",
                c.shot, c.start_s, c.end_s, c.median_confidence, c.lost, c.frames,
                c.header_doubtful ? ", doubtful in the camera path" : "", c.gain);
  return buf;
}

}  // namespace hapcine
