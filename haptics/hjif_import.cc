#include "haptics/hjif_import.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "haptics/hjif_export.h"

namespace hapcine {
namespace {

using nlohmann::json;

// One channel's curve: keyframe times (s) and values (m), times increasing.
struct Curve {
  int actuator = -1, axis = -1;
  std::vector<double> t, v;
  double At(double time) const {
    if (t.empty() || time < t.front() || time > t.back()) return 0;
    const size_t j = std::upper_bound(t.begin(), t.end(), time) - t.begin();
    if (j >= t.size()) return v.back();
    const double u = (time - t[j - 1]) / (t[j] - t[j - 1]);
    return v[j - 1] + u * (v[j] - v[j - 1]);
  }
};

std::string Str(const json& o, const char* key) {
  return o.contains(key) && o[key].is_string() ? o[key].get<std::string>() : "";
}

long long Int(const json& o, const char* key, long long fallback) {
  return o.contains(key) && o[key].is_number_integer() ? o[key].get<long long>() : fallback;
}

// "perception P channel C" for messages.
std::string Where(const json& p, const json& ch) {
  return "perception " + std::to_string(Int(p, "id", -1)) + " channel " +
         std::to_string(Int(ch, "id", -1));
}

int ActuatorOf(const json& p, const json& ch) {
  if (ch.contains("body_part_target") && ch["body_part_target"].is_array()) {
    const auto& parts = ch["body_part_target"];
    auto has = [&](const char* name) { return std::find(parts.begin(), parts.end(), name) != parts.end(); };
    if (has("Head") && parts.size() == 1) return static_cast<int>(Actuator::kHead);
    if (has("Hand") && has("Left") && !has("Right")) return static_cast<int>(Actuator::kLeft);
    if (has("Hand") && has("Right") && !has("Left")) return static_cast<int>(Actuator::kRight);
    throw Error("", Where(p, ch) + ": body_part_target " + parts.dump() +
                        " is not the head, the left hand or the right hand");
  }
  // Any non-empty part of one actuator's body part (a palm is the hand).
  const long long mask = Int(ch, "body_part_mask", 0);
  for (int a = 0; a < kNumActuators; ++a) {
    const long long part = HjifBodyPartMask(static_cast<Actuator>(a));
    if (mask != 0 && (mask & ~part) == 0) return a;
  }
  throw Error("", Where(p, ch) + ": body_part_mask " + std::to_string(mask) +
                      " is not the head, the left hand or the right hand");
}

// Seat axis (0 x, 1 y, 2 z) and sign of the channel's direction.
std::pair<int, double> AxisOf(const json& p, const json& ch) {
  if (!ch.contains("direction")) throw Error("", Where(p, ch) + ": no direction (seat axis)");
  const json& d = ch["direction"];
  const long long c[3] = {Int(d, "X", 0), Int(d, "Y", 0), Int(d, "Z", 0)};
  const int nonzero = (c[0] != 0) + (c[1] != 0) + (c[2] != 0);
  if (nonzero != 1) {
    throw Error("", Where(p, ch) + ": direction " + d.dump() + " is not along X, Y or Z");
  }
  const int axis = c[0] != 0 ? 0 : c[1] != 0 ? 1 : 2;
  return {axis, c[axis] > 0 ? 1.0 : -1.0};
}

// Appends one Basis effect's keyframes to `curve`.
void AppendEffect(const json& p, const json& ch, const json& e, double scale, double timescale,
                  Curve* curve) {
  const std::string type = Str(e, "effect_type");
  if (type != "Basis") {
    throw Error("", Where(p, ch) + ": effect type " + (type.empty() ? "(none)" : type) +
                        " unsupported (Basis effects with keyframes only)");
  }
  const long long position = Int(e, "position", 0);
  if (!e.contains("keyframes") || !e["keyframes"].is_array()) return;
  const size_t start = curve->t.size();
  for (const json& k : e["keyframes"]) {
    if (!k.contains("relative_position") || !k["relative_position"].is_number_integer() ||
        !k.contains("amplitude_modulation") || !k["amplitude_modulation"].is_number()) {
      throw Error("", Where(p, ch) + ": a keyframe without relative_position or amplitude_modulation");
    }
    const double t = (position + Int(k, "relative_position", 0)) / timescale;
    const double v = k["amplitude_modulation"].get<double>() * scale;
    if (!curve->t.empty() && t <= curve->t.back()) {
      // A boundary keyframe shared with the previous effect is the same point.
      if (curve->t.size() > start || t < curve->t.back()) {
        throw Error("", Where(p, ch) + ": keyframes overlap or go back in time at " +
                            std::to_string(t) + " s");
      }
      curve->t.pop_back();
      curve->v.pop_back();
    }
    if (!std::isfinite(v) || std::abs(v) > 1) {
      throw Error("", Where(p, ch) + ": position " + std::to_string(v) + " m at " +
                          std::to_string(t) + " s (beyond 1 m)");
    }
    curve->t.push_back(t);
    curve->v.push_back(v);
  }
}

Curve ReadChannel(const json& p, const json& ch, double unit, double timescale) {
  Curve curve;
  curve.actuator = ActuatorOf(p, ch);
  const auto [axis, sign] = AxisOf(p, ch);
  curve.axis = axis;
  const double gain = ch.contains("gain") && ch["gain"].is_number() ? ch["gain"].get<double>() : 1;
  const auto& bands = ch.contains("bands") ? ch["bands"] : json::array();
  if (bands.size() != 1) {
    throw Error("", Where(p, ch) + ": " + std::to_string(bands.size()) +
                        " bands (one Curve band supported)");
  }
  const json& band = bands[0];
  if (Str(band, "band_type") != "Curve") {
    throw Error("", Where(p, ch) + ": band type " + Str(band, "band_type") +
                        " unsupported (Curve only)");
  }
  const std::string curve_type = Str(band, "curve_type");
  if (!curve_type.empty() && curve_type != "Linear") {
    throw Error("", Where(p, ch) + ": curve type " + curve_type + " unsupported (Linear only)");
  }
  std::vector<const json*> effects;
  if (band.contains("effects") && band["effects"].is_array()) {
    for (const json& e : band["effects"]) effects.push_back(&e);
  }
  std::stable_sort(effects.begin(), effects.end(), [](const json* a, const json* b) {
    return Int(*a, "position", 0) < Int(*b, "position", 0);
  });
  for (const json* e : effects) AppendEffect(p, ch, *e, sign * gain * unit, timescale, &curve);
  return curve;
}

std::vector<Curve> ReadCurves(const json& doc) {
  const double timescale = static_cast<double>(Int(doc, "timescale", 1000));
  if (!(timescale >= 1)) throw Error("", "timescale " + std::to_string(timescale) + " is not positive");
  if (!doc.contains("perceptions") || !doc["perceptions"].is_array()) {
    throw Error("", "no perceptions: not an MPEG-I Haptics (.hjif) file");
  }
  std::vector<Curve> curves;
  bool used[kNumActuators][3] = {};
  for (const json& p : doc["perceptions"]) {
    const std::string modality = Str(p, "perception_modality");
    if (modality != "Position") {
      throw Error("", "perception " + std::to_string(Int(p, "id", -1)) + " (" + modality +
                          "): only Position perceptions can play on the HapSeat");
    }
    const double unit = std::pow(10.0, static_cast<double>(Int(p, "perception_unit_exponent", 0)));
    for (const json& ch : p.value("channels", json::array())) {
      Curve c = ReadChannel(p, ch, unit, timescale);
      if (used[c.actuator][c.axis]) {
        throw Error("", Where(p, ch) + ": a second channel for the " +
                            ActuatorName(static_cast<Actuator>(c.actuator)) + " " +
                            "xyz"[c.axis] + " axis");
      }
      used[c.actuator][c.axis] = true;
      if (!c.t.empty()) curves.push_back(std::move(c));
    }
  }
  if (curves.empty()) throw Error("", "no keyframes in any Position channel");
  return curves;
}

HapticTrack SampleCurves(const std::vector<Curve>& curves, double rate_hz) {
  double t0 = curves[0].t.front(), t1 = curves[0].t.back();
  for (const Curve& c : curves) {
    t0 = std::min(t0, c.t.front());
    t1 = std::max(t1, c.t.back());
  }
  HapticTrack track;
  track.rate_hz = rate_hz;
  const size_t n = static_cast<size_t>(std::floor((t1 - t0) * rate_hz + 1e-9)) + 1;
  track.samples.resize(n);
  for (size_t i = 0; i < n; ++i) {
    HapticSample& s = track.samples[i];
    s.time_s = t0 + i / rate_hz;
    for (const Curve& c : curves) s.pos_m[c.actuator][c.axis] = c.At(s.time_s);
  }
  return track;
}

}  // namespace

HapticTrack HjifToHapticTrack(const json& doc, const std::string& source, double rate_hz) {
  try {
    if (!doc.is_object()) throw Error("", "not a JSON object: not an MPEG-I Haptics (.hjif) file");
    HapticTrack track = SampleCurves(ReadCurves(doc), rate_hz);
    track.model = "hjif";
    track.source = source;
    track.metadata["description"] = Str(doc, "description");
    return track;
  } catch (const Error& e) {
    throw Error(source, e.reason());
  }
}

HapticTrack ReadHjifFile(const std::string& path, double rate_hz) {
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot open");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    throw Error(path, std::string("not JSON: ") + e.what());
  }
  return HjifToHapticTrack(doc, path, rate_hz);
}

bool IsHjifPath(const std::string& path) {
  if (path.size() < 5) return false;
  std::string ext = path.substr(path.size() - 5);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".hjif";
}

HapticTrack ReadAnyHapticTrackFile(const std::string& path) {
  return IsHjifPath(path) ? ReadHjifFile(path) : ReadHapticTrackFile(path);
}

}  // namespace hapcine
