#include "platform/platform_track.h"

#include <cmath>
#include <fstream>

#include "core/csv.h"
#include "core/error.h"
#include "core/header_value.h"
#include "core/input_file.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

const std::vector<std::string> kPoseColumns = {"time_s",    "x_m",     "y_m",     "z_m",
                                               "pitch_deg", "yaw_deg", "roll_deg"};

std::string LegColumn(int i) { return "leg" + std::to_string(i + 1) + "_m"; }

void CheckWritable(const PlatformTrack& track, bool* all_legs, bool* any_shot) {
  if (!(track.rate_hz > 0) || !std::isfinite(track.rate_hz))
    throw Error("platform track", "rate_hz must be positive");
  *all_legs = !track.samples.empty();
  *any_shot = false;
  for (size_t i = 0; i < track.samples.size(); ++i) {
    const PlatformSample& s = track.samples[i];
    bool finite = std::isfinite(s.time_s) && s.pose.allFinite();
    if (s.legs) {
      for (double l : *s.legs) finite &= std::isfinite(l);
    }
    if (!finite) throw Error("platform track", "non-finite value at sample " + std::to_string(i));
    if (i > 0 && s.time_s <= track.samples[i - 1].time_s)
      throw Error("platform track", "time not increasing at sample " + std::to_string(i));
    *all_legs &= s.legs.has_value();
    *any_shot |= s.shot.has_value();
  }
}

PlatformSample ReadRow(const CsvReader& csv, const std::vector<std::string>& f, int c_leg1,
                       int c_shot) {
  PlatformSample s;
  s.time_s = csv.Double(f, 0, "time_s");
  for (int d = 0; d < kNumDofs; ++d) {
    const double v = csv.Double(f, d + 1, kPoseColumns[d + 1].c_str());
    if (IsRotation(d) ? !(std::abs(v) <= 90) : !(std::abs(v) <= 1))
      csv.Fail(kPoseColumns[d + 1] + " out of range (|x| <= 1 m, |angle| <= 90 deg)");
    s.pose[d] = IsRotation(d) ? DegToRad(v) : v;
  }
  if (c_leg1 >= 0) {
    LegLengths legs;
    for (int i = 0; i < 6; ++i) {
      legs[i] = csv.Double(f, c_leg1 + i, "leg");
      if (!(legs[i] > 0 && legs[i] <= 10)) csv.Fail("leg length out of range (0, 10] m");
    }
    s.legs = legs;
  }
  if (c_shot >= 0 && !f[c_shot].empty()) s.shot = csv.Int(f, c_shot, "shot");
  return s;
}

}  // namespace

void WritePlatformTrack(const PlatformTrack& track, std::ostream& out) {
  bool all_legs = false, any_shot = false;
  CheckWritable(track, &all_legs, &any_shot);
  WriteHeaderLine(out, "type", "platform");
  WriteHeaderLine(out, "rate_hz", FormatDouble(track.rate_hz));
  WriteHeaderLine(out, "model", track.model);
  WriteHeaderLine(out, "source", track.source);
  WriteHeaderLine(out, "platform", track.platform);
  WriteHeaderLine(out, "dofs", track.dofs);
  for (const auto& [key, value] : track.metadata) {
    if (key != "type" && key != "rate_hz" && key != "model" && key != "source" &&
        key != "platform" && key != "dofs")
      WriteHeaderLine(out, key, value);
  }
  for (size_t i = 0; i < kPoseColumns.size(); ++i) out << (i ? "," : "") << kPoseColumns[i];
  if (all_legs) {
    for (int i = 0; i < 6; ++i) out << ',' << LegColumn(i);
  }
  if (any_shot) out << ",shot";
  out << "\n";
  for (const PlatformSample& s : track.samples) {
    out << FormatFixed(s.time_s, 6);
    for (int d = 0; d < kNumDofs; ++d)
      out << ',' << (IsRotation(d) ? FormatFixed(RadToDeg(s.pose[d]), 6) : FormatFixed(s.pose[d], 7));
    if (all_legs) {
      for (double l : *s.legs) out << ',' << FormatFixed(l, 7);
    }
    if (any_shot) out << ',' << (s.shot ? std::to_string(*s.shot) : "");
    out << '\n';
  }
}

PlatformTrack ReadPlatformTrack(std::istream& in, const std::string& source_name) {
  CsvReader csv(in, source_name);
  csv.ReadPreamble();
  PlatformTrack track;
  track.metadata = csv.metadata();
  auto take = [&](const char* key, bool required) -> std::string {
    auto it = track.metadata.find(key);
    if (it == track.metadata.end()) {
      if (required) csv.Fail(std::string("missing metadata '# ") + key + "='");
      return "";
    }
    std::string v = it->second;
    track.metadata.erase(it);
    return v;
  };
  if (take("type", true) != "platform") csv.Fail("not a platform track ('# type=platform')");
  const std::string rate = take("rate_hz", true);
  char* end = nullptr;
  track.rate_hz = std::strtod(rate.c_str(), &end);
  if (end == rate.c_str() || *end != '\0' || !(track.rate_hz > 0 && track.rate_hz <= 100000))
    csv.Fail("rate_hz '" + rate + "' is not a positive rate");
  track.model = take("model", true);
  track.source = take("source", true);
  track.platform = take("platform", false);
  track.dofs = take("dofs", false);
  csv.RequireLeadingColumns(kPoseColumns);
  const int c_leg1 = csv.Column(LegColumn(0));
  for (int i = 1; c_leg1 >= 0 && i < 6; ++i) {
    if (csv.Column(LegColumn(i)) != c_leg1 + i) csv.Fail("leg columns must be leg1_m..leg6_m in order");
  }
  const int c_shot = csv.Column("shot");
  std::vector<std::string> f;
  while (csv.NextRow(&f)) {
    PlatformSample s = ReadRow(csv, f, c_leg1, c_shot);
    if (!track.samples.empty() && !(s.time_s > track.samples.back().time_s))
      csv.Fail("time_s not increasing");
    track.samples.push_back(std::move(s));
  }
  return track;
}

PlatformTrack ReadPlatformTrackFile(const std::string& path) {
  InputFile in(path);
  return ReadPlatformTrack(in.stream(), path);
}

bool LooksLikePlatformTrackFile(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && !line.empty() && line[0] == '#') {
    if (line.rfind("# type=platform", 0) == 0) return true;
  }
  return false;
}

}  // namespace hapcine
