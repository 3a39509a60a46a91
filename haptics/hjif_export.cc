#include "haptics/hjif_export.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace hapcine {
namespace {

using nlohmann::json;

// The int8 unit of a direction vector (reference software VECTOR_RANGE).
constexpr int kUnitVector = 127;
// Amplitudes are millimetres / gain (perception_unit_exponent -3): a gain
// in mm keeps its precision in the binary format, which stores the gain as
// a float32 fraction of +-10000 (0.05 would come back as 0.0498).
constexpr int kPerceptionUnitExponent = -3;
constexpr double kUnitsPerMetre = 1000;

// The creation day at midnight UTC (the schema wants a date-time): the same
// track made twice in a day is the same file (batch compares a Slurm run's
// outputs with a local run's); SOURCE_DATE_EPOCH, the reproducible-builds
// convention, fixes the day.
std::string NowUtc() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (end != epoch && *end == '\0' && v >= 0) now = static_cast<std::time_t>(v);
  }
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT00:00:00Z", &tm);
  return buf;
}

// Length of the UTF-8 character at s[i] (0 if the bytes there are not one).
size_t Utf8CharLength(const std::string& s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  const size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return 0;
  }
  return n;
}

}  // namespace

uint32_t HjifBodyPartMask(Actuator a) {
  // The reference software's body model (Tools/include/OHMData.h, `Body`):
  // HEAD = front | back | right | left (bits 0-3); a hand = its palm, dorsum
  // and fingers (right: bits 16, 18, 20; left: 17, 19, 21).
  switch (a) {
    case Actuator::kHead: return 0x0000000Fu;
    case Actuator::kLeft: return 0x002A0000u;
    case Actuator::kRight: return 0x00150000u;
  }
  return 0;
}

std::string HjifShortText(const std::string& text, size_t max_bytes) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    const size_t n = Utf8CharLength(text, i);
    const bool control = n == 1 && static_cast<unsigned char>(text[i]) < 0x20;
    const std::string c = n == 0 || control ? "?" : text.substr(i, n);
    if (out.size() + c.size() > max_bytes) break;
    out += c;
    i += std::max<size_t>(n, 1);
  }
  return out;
}

void HjifOptions::Check() const {
  if (!(keyframe_rate_hz > 0 && keyframe_rate_hz <= 10000)) {
    throw UsageError("hjif keyframe rate must be in (0, 10000] Hz");
  }
  // 48000: the Main profile's largest timescale (reference software check).
  if (!(timescale >= 1 && timescale <= 48000)) throw UsageError("hjif timescale must be in [1, 48000]");
  // Two keyframes must fit in one effect's 16-bit relative positions.
  if (timescale / keyframe_rate_hz > kHjifMaxRelativePosition / 2) {
    throw UsageError("hjif keyframe interval exceeds half of the 65535 ticks an effect can span");
  }
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
  // A regular keyframe at least one tick before the last sample: no two
  // keyframes share a tick.
  while (!(k.t0 + k.count * k.step > k.t1 - 1.0 / o.timescale)) ++k.count;
  ++k.count;  // the last sample
  return k;
}

// One effect: keyframes [first, last] (inclusive) of every channel, at
// `position` ticks. Consecutive effects share their boundary keyframe, so
// the curve has no gap, and none spans more than 65535 ticks.
struct EffectSpan {
  size_t first = 0, last = 0;
  long long position = 0;
};

long long Ticks(double t, const HjifOptions& o) { return std::llround(t * o.timescale); }

std::vector<EffectSpan> EffectSpansOf(const KeyframeTimes& times, const HjifOptions& o) {
  std::vector<EffectSpan> spans;
  size_t first = 0;
  while (true) {
    EffectSpan span{first, first, Ticks(times.At(first), o)};
    while (span.last + 1 < times.count &&
           Ticks(times.At(span.last + 1), o) - span.position <= kHjifMaxRelativePosition) {
      ++span.last;
    }
    spans.push_back(span);
    if (span.last + 1 >= times.count) break;
    first = span.last;
  }
  return spans;
}

// One keyframe: {relative_position, amplitude_modulation}.
struct Keyframe {
  long long relative_position;
  double amplitude;
};

// Calls visit(Keyframe) for each keyframe of channel (a, k) in `span`.
template <class Visit>
void ForEachKeyframe(const HapticTrack& track, const HjifOptions& o, const KeyframeTimes& times,
                     const EffectSpan& span, int a, int k, Visit visit) {
  size_t hint = 0;
  Eigen::Vector3d pos[kNumActuators];
  const double gain = o.gain_m * kUnitsPerMetre;
  for (size_t i = span.first; i <= span.last; ++i) {
    const double t = times.At(i);
    track.Sample(t, pos, &hint);  // the track interpolated linearly
    visit(Keyframe{Ticks(t, o) - span.position, pos[a][k] * kUnitsPerMetre / gain});
  }
}

std::string DescriptionOf(const HapticTrack& track, const HjifOptions& o) {
  const std::string text = o.description.empty()
                               ? std::filesystem::path(track.source).stem().string()
                               : o.description;
  return HjifShortText(text, kHjifMaxDescriptionBytes);
}

json HjifChannel(int a, int k, const HjifOptions& o, json effects) {
  const char* axis_names[3] = {"x", "y", "z"};
  json band = {{"band_type", "Curve"},
               {"curve_type", "Linear"},
               {"lower_frequency_limit", 0},
               {"upper_frequency_limit",
                std::max(1, static_cast<int>(std::lround(o.keyframe_rate_hz / 2)))},
               {"effects", std::move(effects)}};
  json ch;
  ch["id"] = a * 3 + k;
  ch["description"] = std::string(ActuatorName(static_cast<Actuator>(a))) + " " +
                      axis_names[k] + " position (seat frame: +X right, +Y up, +Z backward)";
  ch["gain"] = o.gain_m * kUnitsPerMetre;
  ch["mixing_coefficient"] = 1.0;
  ch["body_part_mask"] = HjifBodyPartMask(static_cast<Actuator>(a));
  ch["reference_device_id"] = 1;
  // The seat axis this channel moves along, an int8 unit vector.
  ch["direction"] = {{"X", k == 0 ? kUnitVector : 0},
                     {"Y", k == 1 ? kUnitVector : 0},
                     {"Z", k == 2 ? kUnitVector : 0}};
  ch["bands"] = json::array({band});
  return ch;
}

json HjifPerception(int a, const HjifOptions& o, const std::function<json(int, int)>& effects) {
  const Actuator actuator = static_cast<Actuator>(a);
  json p;
  p["id"] = a;
  p["perception_modality"] = "Position";
  p["description"] =
      std::string(ActuatorName(actuator)) + " actuator displacement from its workspace centre";
  p["avatar_id"] = 1;
  p["effect_library"] = json::array();
  p["reference_devices"] = json::array(
      {json{{"id", 1}, {"name", "Novint Falcon"}, {"body_part_mask", HjifBodyPartMask(actuator)}}});
  p["unit_exponent"] = -3;  // of time: the timescale's ticks are ms at 1000
  p["perception_unit_exponent"] = kPerceptionUnitExponent;  // amplitude x gain is mm
  json channels = json::array();
  for (int k = 0; k < 3; ++k) channels.push_back(HjifChannel(a, k, o, effects(a, k)));
  p["channels"] = channels;
  return p;
}

// The document with each channel's effects array made by effects(a, k).
json HjifDocument(const HapticTrack& track, const HjifOptions& o,
                  const std::function<json(int, int)>& effects) {
  json doc;
  doc["version"] = "2023";
  doc["profile"] = "Main";
  doc["level"] = 1;
  doc["date"] = o.date.empty() ? NowUtc() : o.date;
  doc["timescale"] = o.timescale;
  doc["description"] = DescriptionOf(track, o);
  // Ids start at 1 (0 is reserved); a Custom avatar needs a mesh in the
  // binary format: a URN names the HapSeat's seated user (no file).
  doc["avatars"] =
      json::array({json{{"id", 1}, {"lod", 0}, {"type", "Custom"}, {"mesh", "urn:hapcine:hapseat"}}});
  json perceptions = json::array();
  for (int a = 0; a < kNumActuators; ++a) perceptions.push_back(HjifPerception(a, o, effects));
  doc["perceptions"] = perceptions;
  // What the reference decoder puts back after a binary round trip.
  doc["syncs"] = json::array({json{{"timestamp", 0}, {"timescale", o.timescale}}});
  return doc;
}

void CheckTrack(const HapticTrack& track, const HjifOptions& o) {
  o.Check();
  if (track.samples.empty()) throw Error(track.source, "haptic track has no samples");
  const double t0 = track.samples.front().time_s;
  const double t1 = track.samples.back().time_s;
  if (t0 < 0) throw Error(track.source, "a .hjif cannot start before time 0");
  if (Ticks(t1, o) > kHjifMaxEffectPosition) {
    throw Error(track.source, "track ends at " + std::to_string(t1) +
                                  " s, beyond the .hjif effect position limit (2^25 ticks)");
  }
}

json EffectHeader(const EffectSpan& span) {
  return json{{"effect_type", "Basis"}, {"position", span.position}};
}

// The line `"effects": "<placeholder a k>"` of the skeleton, as dump(1)
// prints it: its indentation, channel and trailing comma. A user's text
// cannot make such a line: dump() escapes the control characters of every string.
const char kPlaceholder[] = "\"effects\": \"\\u0000hapcine effects ";

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

// One effect as dump(1) prints it at `pad`: its members in key order
// (effect_type, keyframes, position).
template <class Keyframes>
void WriteEffect(std::ostream& out, const std::string& pad, const EffectSpan& span, bool last,
                 Keyframes keyframes) {
  out << pad << "{\n"
      << pad << " \"effect_type\": \"Basis\",\n"
      << pad << " \"keyframes\": [\n";
  keyframes(pad + "  ");
  out << pad << " ],\n"
      << pad << " \"position\": " << span.position << "\n"
      << pad << (last ? "}\n" : "},\n");
}

}  // namespace

json HapticTrackToHjif(const HapticTrack& track, const HjifOptions& o) {
  CheckTrack(track, o);
  const KeyframeTimes times = KeyframeTimesOf(track, o);
  const std::vector<EffectSpan> spans = EffectSpansOf(times, o);
  return HjifDocument(track, o, [&](int a, int k) {
    json effects = json::array();
    for (const EffectSpan& span : spans) {
      json effect = EffectHeader(span);
      json keyframes = json::array();
      ForEachKeyframe(track, o, times, span, a, k, [&](const Keyframe& key) {
        keyframes.push_back({{"relative_position", key.relative_position},
                             {"amplitude_modulation", key.amplitude}});
      });
      effect["keyframes"] = std::move(keyframes);
      effects.push_back(std::move(effect));
    }
    return effects;
  });
}

void WriteHjif(const HapticTrack& track, const HjifOptions& o, std::ostream& out) {
  CheckTrack(track, o);
  const KeyframeTimes times = KeyframeTimesOf(track, o);
  const std::vector<EffectSpan> spans = EffectSpansOf(times, o);
  // The document without its effects (a few kB), each effects array
  // replaced by a placeholder string, then printed line by line with the
  // effects written in place of each placeholder: a long film's millions
  // of keyframes are never held in memory.
  const json skeleton = HjifDocument(track, o, [](int a, int k) {
    return json(std::string(1, '\0') + "hapcine effects " + std::to_string(a) + " " +
                std::to_string(k));
  });
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
    out << pad << "\"effects\": [\n";
    for (size_t e = 0; e < spans.size(); ++e) {
      WriteEffect(out, pad + " ", spans[e], e + 1 == spans.size(), [&](const std::string& kpad) {
        size_t i = spans[e].first;
        ForEachKeyframe(track, o, times, spans[e], a, k, [&](const Keyframe& key) {
          WriteKeyframe(out, kpad, key, i++ == spans[e].last);
        });
      });
    }
    out << pad << (comma ? "],\n" : "]\n");
  }
}

void WriteHjifFile(const HapticTrack& track, const std::string& path, const HjifOptions& o) {
  AtomicFile file(path);
  WriteHjif(track, o, file.stream());
  file.Commit();
}

}  // namespace hapcine
