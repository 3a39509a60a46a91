#include "haptics/hjif_export.h"

#include <algorithm>
#include <cmath>
#include <ctime>

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

json HapticTrackToHjif(const HapticTrack& track, const HjifOptions& o) {
  o.Check();
  if (track.samples.empty()) throw Error(track.source, "haptic track has no samples");
  const double t0 = track.samples.front().time_s;
  const double t1 = track.samples.back().time_s;
  // Keyframe times: every 1/keyframe_rate_hz from t0, plus the last sample.
  std::vector<double> key_t;
  const double step = 1.0 / o.keyframe_rate_hz;
  for (size_t i = 0;; ++i) {
    const double t = t0 + i * step;
    if (t > t1 - 1e-9) break;
    key_t.push_back(t);
  }
  key_t.push_back(t1);
  // Positions at the keyframes (the track interpolated linearly).
  std::vector<std::array<Eigen::Vector3d, kNumActuators>> key_pos(key_t.size());
  size_t hint = 0;
  for (size_t i = 0; i < key_t.size(); ++i) track.Sample(key_t[i], key_pos[i].data(), &hint);
  const long long effect_pos = std::llround(t0 * o.timescale);

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
  doc["avatars"] = json::array({json{{"id", 0}, {"lod", 0}, {"type", "Custom"}}});
  json perceptions = json::array();
  const char* axis_names[3] = {"x", "y", "z"};
  for (int a = 0; a < kNumActuators; ++a) {
    json p;
    p["id"] = a;
    p["perception_modality"] = "Position";
    p["description"] = std::string(ActuatorName(static_cast<Actuator>(a))) +
                       " actuator displacement from its workspace centre";
    p["avatar_id"] = 0;
    p["effect_library"] = json::array();
    p["reference_devices"] = json::array(
        {json{{"id", 0}, {"name", "Novint Falcon"}}});
    p["unit_exponent"] = 0;             // metres (10^0)
    p["perception_unit_exponent"] = 0;  // amplitudes times gain are metres
    json channels = json::array();
    for (int k = 0; k < 3; ++k) {
      json keyframes = json::array();
      for (size_t i = 0; i < key_t.size(); ++i) {
        keyframes.push_back(
            {{"relative_position", std::llround(key_t[i] * o.timescale) - effect_pos},
             {"amplitude_modulation", key_pos[i][a][k] / o.gain_m}});
      }
      json effect = {{"id", 0},    {"effect_type", "Basis"}, {"position", effect_pos},
                     {"phase", 0}, {"base_signal", "Sine"},  {"keyframes", keyframes}};
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
      ch["reference_device_id"] = 0;
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

void WriteHjifFile(const HapticTrack& track, const std::string& path, const HjifOptions& o) {
  const json doc = HapticTrackToHjif(track, o);
  AtomicFile file(path);
  file.stream() << doc.dump(1) << "\n";
  file.Commit();
}

}  // namespace hapcine
