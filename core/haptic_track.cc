#include "core/haptic_track.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/header_value.h"
#include "core/input_file.h"
#include "core/line_count.h"

namespace hapcine {
namespace {

const std::vector<std::string> kRequired = {"time_s", "head_x",  "head_y",  "head_z",
                                            "left_x", "left_y",  "left_z",  "right_x",
                                            "right_y", "right_z"};
// A Falcon's workspace is ~0.1 m; anything beyond 1 m is a unit mistake.
constexpr double kAbsurdPositionM = 1.0;

// The slope of a monotone cubic at a row between an interval of length h0
// and slope d0 and one of length h1 and slope d1: the three-point derivative
// (exact for quadratics), zero at a local extremum or flat, and at most three
// times the smaller secant, which keeps each piece monotone (Fritsch-Carlson).
double MonotoneSlope(double h0, double d0, double h1, double d1) {
  if (!(d0 * d1 > 0)) return 0;
  const double m = (h1 * d0 + h0 * d1) / (h0 + h1);
  const double limit = 3 * std::min(std::abs(d0), std::abs(d1));
  return std::abs(m) <= limit ? m : std::copysign(limit, d0);
}

// Rows i and i+1 of the track at w in [0, 1] between them: cubic Hermite,
// with the neighbours i-1 and i+2 (when they exist) for the slopes.
void MonotoneCubic(const std::vector<HapticSample>& s, size_t i, double w,
                   Eigen::Vector3d out[kNumActuators]) {
  const double h = s[i + 1].time_s - s[i].time_s;
  const double w2 = w * w, w3 = w2 * w;
  const double h00 = 2 * w3 - 3 * w2 + 1, h10 = w3 - 2 * w2 + w;
  const double h01 = -2 * w3 + 3 * w2, h11 = w3 - w2;
  const bool has_before = i > 0, has_after = i + 2 < s.size();
  const double h_before = has_before ? s[i].time_s - s[i - 1].time_s : 0;
  const double h_after = has_after ? s[i + 2].time_s - s[i + 1].time_s : 0;
  for (int a = 0; a < kNumActuators; ++a) {
    for (int k = 0; k < 3; ++k) {
      const double pa = s[i].pos_m[a][k], pb = s[i + 1].pos_m[a][k];
      const double d = (pb - pa) / h;
      // The end rows take the secant: a line there, never an overshoot.
      const double ma = has_before
                            ? MonotoneSlope(h_before, (pa - s[i - 1].pos_m[a][k]) / h_before, h, d)
                            : d;
      const double mb =
          has_after ? MonotoneSlope(h, d, h_after, (s[i + 2].pos_m[a][k] - pb) / h_after) : d;
      const double v = h00 * pa + h10 * h * ma + h01 * pb + h11 * h * mb;
      // Mathematically inside [pa, pb] already; the clamp absorbs rounding.
      out[a][k] = std::clamp(v, std::min(pa, pb), std::max(pa, pb));
    }
  }
}

}  // namespace

const char* TrackInterpolationName(TrackInterpolation i) {
  return i == TrackInterpolation::kMonotoneCubic ? "monotone_cubic" : "linear";
}

TrackInterpolation InterpolationForRate(double rate_hz) {
  constexpr double kPlayerLoopHz = 1000;
  return rate_hz < kPlayerLoopHz ? TrackInterpolation::kMonotoneCubic : TrackInterpolation::kLinear;
}

const char* ActuatorName(Actuator a) {
  switch (a) {
    case Actuator::kHead: return "head";
    case Actuator::kLeft: return "left";
    case Actuator::kRight: return "right";
  }
  return "?";
}

void HapticTrack::Sample(double t, Eigen::Vector3d out[kNumActuators],
                         size_t* hint) const {
  if (samples.empty()) {
    for (int a = 0; a < kNumActuators; ++a) out[a].setZero();
    return;
  }
  if (!(t > samples.front().time_s)) {  // also catches NaN
    for (int a = 0; a < kNumActuators; ++a) out[a] = samples.front().pos_m[a];
    return;
  }
  if (t >= samples.back().time_s) {
    for (int a = 0; a < kNumActuators; ++a) out[a] = samples.back().pos_m[a];
    return;
  }
  size_t i = hint ? std::min(*hint, samples.size() - 2) : 0;
  // Monotone playback: walk forward from the hint; a seek backwards rescans.
  if (samples[i].time_s > t) i = 0;
  if (samples[i + 1].time_s <= t) {
    if (hint && i + 2 < samples.size() && samples[i + 2].time_s > t) {
      ++i;
    } else {
      auto it = std::upper_bound(samples.begin(), samples.end(), t,
                                 [](double v, const HapticSample& s) { return v < s.time_s; });
      i = static_cast<size_t>(it - samples.begin()) - 1;
    }
  }
  const HapticSample& a = samples[i];
  const HapticSample& b = samples[i + 1];
  const double w = (t - a.time_s) / (b.time_s - a.time_s);
  if (interpolation == TrackInterpolation::kMonotoneCubic) {
    MonotoneCubic(samples, i, w, out);
  } else {
    for (int k = 0; k < kNumActuators; ++k) out[k] = (1 - w) * a.pos_m[k] + w * b.pos_m[k];
  }
  if (hint) *hint = i;
}

HapticTrack ReadHapticTrack(std::istream& in, const std::string& source_name) {
  // The shortest row: ten one-digit fields.
  const size_t rows = CountLinesAhead(in, 19);
  CsvReader csv(in, source_name);
  csv.ReadPreamble();
  HapticTrack track;
  track.metadata = csv.metadata();
  auto take = [&](const char* key) -> std::string {
    auto it = track.metadata.find(key);
    if (it == track.metadata.end()) csv.Fail(std::string("missing metadata '# ") + key + "='");
    std::string v = it->second;
    track.metadata.erase(it);
    return v;
  };
  const std::string rate = take("rate_hz");
  char* end = nullptr;
  track.rate_hz = std::strtod(rate.c_str(), &end);
  if (end == rate.c_str() || *end != '\0' || !std::isfinite(track.rate_hz) ||
      track.rate_hz <= 0 || track.rate_hz > 100000) {
    csv.Fail("rate_hz '" + rate + "' is not a positive rate");
  }
  track.model = take("model");
  track.source = take("source");
  if (auto it = track.metadata.find("interpolation"); it != track.metadata.end()) {
    if (it->second == TrackInterpolationName(TrackInterpolation::kMonotoneCubic)) {
      track.interpolation = TrackInterpolation::kMonotoneCubic;
    } else if (it->second != TrackInterpolationName(TrackInterpolation::kLinear)) {
      csv.Fail("interpolation '" + it->second + "' is not linear or monotone_cubic");
    }
    track.metadata.erase(it);
  }
  csv.RequireLeadingColumns(kRequired);
  const int c_shot = csv.Column("shot");
  const int c_effect = csv.Column("effect");

  TryReserve(&track.samples, rows);
  RecentName effects;
  std::vector<std::string> f;
  while (csv.NextRow(&f)) {
    HapticSample s;
    s.time_s = csv.Double(f, 0, "time_s");
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        const int col = 1 + 3 * a + k;
        s.pos_m[a][k] = csv.Double(f, col, kRequired[col].c_str());
        if (std::abs(s.pos_m[a][k]) > kAbsurdPositionM) {
          csv.Fail("'" + kRequired[col] + "' = " + f[col] + " m is beyond any workspace");
        }
      }
    }
    if (c_shot >= 0 && !f[c_shot].empty()) s.shot = csv.Int(f, c_shot, "shot");
    if (c_effect >= 0 && !f[c_effect].empty() && !effects.Make(f[c_effect], &s.effect)) {
      csv.Fail("too many distinct values in column 'effect'");
    }
    if (!track.samples.empty() && s.time_s <= track.samples.back().time_s) {
      csv.Fail("time_s is not increasing");
    }
    track.samples.push_back(std::move(s));
  }
  if (track.samples.empty()) csv.Fail("no data rows");
  return track;
}

HapticTrack ReadHapticTrackFile(const std::string& file) {
  InputFile in(file);
  return ReadHapticTrack(in.stream(), file);
}

void WriteHapticTrack(const HapticTrack& track, std::ostream& out) {
  if (!(track.rate_hz > 0) || !std::isfinite(track.rate_hz)) {
    throw Error("haptic track", "rate_hz must be positive");
  }
  bool any_shot = false, any_effect = false;
  for (size_t i = 0; i < track.samples.size(); ++i) {
    const HapticSample& s = track.samples[i];
    bool finite = std::isfinite(s.time_s);
    for (int a = 0; a < kNumActuators; ++a) finite &= s.pos_m[a].allFinite();
    if (!finite) throw Error("haptic track", "non-finite value at sample " + std::to_string(i));
    if (i > 0 && s.time_s <= track.samples[i - 1].time_s) {
      throw Error("haptic track", "time not increasing at sample " + std::to_string(i));
    }
    any_shot |= s.shot.has_value();
    any_effect |= s.effect.has_value();
  }
  WriteHeaderLine(out, "rate_hz", FormatDouble(track.rate_hz));
  WriteHeaderLine(out, "model", track.model);
  WriteHeaderLine(out, "source", track.source);
  // Linear tracks carry no line: they stay as readers before it knew them.
  if (track.interpolation != TrackInterpolation::kLinear) {
    WriteHeaderLine(out, "interpolation", TrackInterpolationName(track.interpolation));
  }
  for (const auto& [key, value] : track.metadata) {
    if (key != "rate_hz" && key != "model" && key != "source" && key != "interpolation") {
      WriteHeaderLine(out, key, value);
    }
  }
  for (size_t i = 0; i < kRequired.size(); ++i) out << (i ? "," : "") << kRequired[i];
  if (any_shot) out << ",shot";
  if (any_effect) out << ",effect";
  out << "\n";
  for (const HapticSample& s : track.samples) {
    out << FormatFixed(s.time_s, 6);
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) out << ',' << FormatFixed(s.pos_m[a][k], 7);
    }
    if (any_shot) out << ',' << (s.shot ? std::to_string(*s.shot) : "");
    if (any_effect) out << ',' << s.effect.value_or("");
    out << '\n';
  }
}

void WriteHapticTrackFile(const HapticTrack& track, const std::string& file) {
  AtomicFile out(file);
  WriteHapticTrack(track, out.stream());
  out.Commit();
}

}  // namespace hapcine
