#include "haptics/hjif_export.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine {
namespace {

using nlohmann::json;

// body_part_target of each actuator's channels (reference-software names).
const nlohmann::json kBodyParts[kNumActuators] = {
    nlohmann::json::array({"Head"}),
    nlohmann::json::array({"Left", "Hand"}),
    nlohmann::json::array({"Right", "Hand"}),
};

std::string TodayUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

}  // namespace

void HjifOptions::Check() const {
  if (!(keyframe_rate_hz > 0 && keyframe_rate_hz <= 10000)) {
    throw UsageError("hjif keyframe rate must be in (0, 10000] Hz");
  }
  if (!(timescale >= 1 && timescale <= 1000000)) throw UsageError("hjif timescale out of range");
  if (!(gain_m > 0 && gain_m <= 1)) throw UsageError("hjif gain must be in (0, 1] m");
}

namespace {

// Keyframe times: every 1/keyframe_rate_hz from the first sample, plus the
// last sample. Computed per index, so no list of times is kept.
struct KeyframeTimes {
  double t0 = 0, t1 = 0, step = 0;
  size_t count = 0;
  double At(size_t i) const { return i + 1 == count ? t1 : t0 + i * step; }
};

KeyframeTimes KeyframeTimesOf(const HapticTrack& track, const HjifOptions& o) {
  KeyframeTimes k;
  k.t0 = track.samples.front().time_s;
  k.t1 = track.samples.back().time_s;
  k.step = 1.0 / o.keyframe_rate_hz;
  while (!(k.t0 + k.count * k.step > k.t1 - 1e-9)) ++k.count;
  ++k.count;  // the last sample
  return k;
}

// One keyframe of actuator a, axis k: {relative_position, amplitude_modulation}.
struct Keyframe {
  long long relative_position;
  double amplitude;
};

// Calls visit(Keyframe) for each keyframe of channel (a, k), in order.
template <class Visit>
void ForEachKeyframe(const HapticTrack& track, const HjifOptions& o, const KeyframeTimes& times,
                     int a, int k, Visit visit) {
  const long long effect_pos = std::llround(times.t0 * o.timescale);
  size_t hint = 0;
  Eigen::Vector3d pos[kNumActuators];
  for (size_t i = 0; i < times.count; ++i) {
    const double t = times.At(i);
    track.Sample(t, pos, &hint);  // the track interpolated linearly
    visit(Keyframe{std::llround(t * o.timescale) - effect_pos, pos[a][k] / o.gain_m});
  }
}

// The document with each channel's keyframes array made by keyframes(a, k).
template <class MakeKeyframes>
json HjifDocument(const HapticTrack& track, const HjifOptions& o, const KeyframeTimes& times,
                  MakeKeyframes keyframes) {
  const long long effect_pos = std::llround(times.t0 * o.timescale);
  json doc;
  doc["version"] = "2023";
  doc["profile"] = "Main";
  doc["level"] = 1;
  doc["date"] = o.date.empty() ? TodayUtc() : o.date;
  doc["timescale"] = o.timescale;
  doc["description"] = o.description.empty()
                           ? "hapcine " + track.model + " haptic track of " + track.source +
                                 " (HapSeat actuator positions, seat frame +X right, +Y up, "
                                 "+Z backward)"
                           : o.description;
  // Avatar and reference-device ids start at 1 (the reference software's schema).
  doc["avatars"] = json::array({json{{"id", 1}, {"lod", 0}, {"type", "Custom"}}});
  json perceptions = json::array();
  const char* axis_names[3] = {"x", "y", "z"};
  for (int a = 0; a < kNumActuators; ++a) {
    json p;
    p["id"] = a;
    p["perception_modality"] = "Position";
    p["description"] = std::string(ActuatorName(static_cast<Actuator>(a))) +
                       " actuator displacement from its workspace centre";
    p["avatar_id"] = 1;
    p["effect_library"] = json::array();
    p["reference_devices"] = json::array(
        {json{{"id", 1}, {"name", "Novint Falcon"}}});
    p["unit_exponent"] = 0;             // metres (10^0)
    p["perception_unit_exponent"] = 0;  // amplitudes times gain are metres
    json channels = json::array();
    for (int k = 0; k < 3; ++k) {
      json effect = {{"id", 0},    {"effect_type", "Basis"}, {"position", effect_pos},
                     {"phase", 0}, {"base_signal", "Sine"},  {"keyframes", keyframes(a, k)}};
      json band = {{"band_type", "Curve"},
                   {"curve_type", "Linear"},
                   {"lower_frequency_limit", 0},
                   // An integer in the reference software's loader.
                   {"upper_frequency_limit",
                    std::max(1, static_cast<int>(std::lround(o.keyframe_rate_hz / 2)))},
                   {"effects", json::array({effect})}};
      json ch;
      ch["id"] = a * 3 + k;
      ch["description"] = std::string(ActuatorName(static_cast<Actuator>(a))) + " " +
                          axis_names[k] + " position (seat frame: +X right, +Y up, +Z backward)";
      ch["gain"] = o.gain_m;
      ch["mixing_coefficient"] = 1.0;
      ch["body_part_mask"] = 0;  // unspecified; body_part_target names the part
      ch["body_part_target"] = kBodyParts[a];
      ch["reference_device_id"] = 1;
      // The seat axis this channel moves along.
      ch["direction"] = {{"X", k == 0 ? 1 : 0}, {"Y", k == 1 ? 1 : 0}, {"Z", k == 2 ? 1 : 0}};
      ch["bands"] = json::array({band});
      channels.push_back(ch);
    }
    p["channels"] = channels;
    perceptions.push_back(p);
  }
  doc["perceptions"] = perceptions;
  doc["syncs"] = json::array();
  return doc;
}

void CheckTrack(const HapticTrack& track, const HjifOptions& o) {
  o.Check();
  if (track.samples.empty()) throw Error(track.source, "haptic track has no samples");
}

// The line `"keyframes": "<placeholder a k>"` of the skeleton, as dump(1)
// prints it: its indentation, channel and trailing comma. A user's text
// cannot make such a line: dump() escapes the newlines of every string.
const char kPlaceholder[] = "\"keyframes\": \"\\u0000hapcine keyframes ";

bool ParsePlaceholderLine(const std::string& line, size_t* indent, int* a, int* k,
                          bool* comma) {
  *indent = line.find_first_not_of(' ');
  if (*indent == std::string::npos || line.compare(*indent, sizeof kPlaceholder - 1,
                                                   kPlaceholder) != 0) {
    return false;
  }
  const size_t p = *indent + sizeof kPlaceholder - 1;
  if (line.size() < p + 4) return false;
  *a = line[p] - '0';
  *k = line[p + 2] - '0';
  *comma = line.back() == ',';
  return true;
}

// One keyframe as dump(1) prints it at `indent` (numbers via nlohmann::json,
// so the text is the one the document's dump() would give).
void WriteKeyframe(std::ostream& out, const std::string& indent, const Keyframe& key,
                   bool last) {
  out << indent << "{\n"
      << indent << " \"amplitude_modulation\": " << json(key.amplitude).dump() << ",\n"
      << indent << " \"relative_position\": " << key.relative_position << "\n"
      << indent << (last ? "}\n" : "},\n");
}

}  // namespace

json HapticTrackToHjif(const HapticTrack& track, const HjifOptions& o) {
  CheckTrack(track, o);
  const KeyframeTimes times = KeyframeTimesOf(track, o);
  return HjifDocument(track, o, times, [&](int a, int k) {
    json keyframes = json::array();
    ForEachKeyframe(track, o, times, a, k, [&](const Keyframe& key) {
      keyframes.push_back({{"relative_position", key.relative_position},
                           {"amplitude_modulation", key.amplitude}});
    });
    return keyframes;
  });
}

void WriteHjif(const HapticTrack& track, const HjifOptions& o, std::ostream& out) {
  CheckTrack(track, o);
  const KeyframeTimes times = KeyframeTimesOf(track, o);
  // The document without its keyframes (a few kB), each keyframes array
  // replaced by a placeholder string, then printed line by line with the
  // keyframes written in place of each placeholder: a long film's millions
  // of keyframes are never held in memory.
  const json skeleton = HjifDocument(track, o, times, [](int a, int k) {
    return std::string(1, '\0') + "hapcine keyframes " + std::to_string(a) + " " +
           std::to_string(k);
  });
  // A file name in the description may hold bytes that are not UTF-8: they
  // become U+FFFD (JSON text is UTF-8) rather than failing the export.
  std::istringstream text(skeleton.dump(1, ' ', false, json::error_handler_t::replace));
  std::string line;
  while (std::getline(text, line)) {
    size_t indent;
    int a, k;
    bool comma;
    if (!ParsePlaceholderLine(line, &indent, &a, &k, &comma)) {
      out << line << '\n';
      continue;
    }
    const std::string pad(indent, ' ');
    out << pad << "\"keyframes\": [\n";
    size_t i = 0;
    ForEachKeyframe(track, o, times, a, k, [&](const Keyframe& key) {
      WriteKeyframe(out, pad + " ", key, ++i == times.count);
    });
    out << pad << (comma ? "],\n" : "]\n");
  }
}

void WriteHjifFile(const HapticTrack& track, const std::string& path, const HjifOptions& o) {
  AtomicFile file(path);
  WriteHjif(track, o, file.stream());
  file.Commit();
}

}  // namespace hapcine
