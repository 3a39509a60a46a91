#include "haptics/haptic_edits.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

constexpr const char* kFormatName = "hapcine-edits";
constexpr int kFormatVersion = 1;

// Parsing context: the file's name for Error, the JSON path for the reason.
struct Reader {
  const std::string& source;
  [[noreturn]] void Fail(const std::string& field, const std::string& reason) const {
    throw Error(source, field + ": " + reason);
  }
};

bool IsExtensionKey(const std::string& key) { return key.rfind("x-", 0) == 0; }

// Text from the file as an error message shows it: control characters as
// \xHH (the message stays one line), at most 60 bytes.
std::string Shown(const std::string& text) {
  size_t cut = std::min<size_t>(text.size(), 60);
  // Not inside a UTF-8 character: the message may become JSON (the studio's errors).
  while (cut < text.size() && cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  std::string out;
  for (const char c : text.substr(0, cut)) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      const char* hex = "0123456789abcdef";
      out += std::string("\\x") + hex[(c >> 4) & 0xf] + hex[c & 0xf];
    } else {
      out += c;
    }
  }
  return cut < text.size() ? out + "..." : out;
}

void CheckKeys(const Reader& r, const json& object, const std::string& field,
               std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    const std::string& key = item.key();
    if (IsExtensionKey(key)) continue;
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
      r.Fail(field.empty() ? Shown(key) : field + "." + Shown(key),
             "unknown key (a typo? keys of your own start with \"x-\")");
    }
  }
}

// A finite number in [lo, hi] (an open end when the flag says so).
double NumberIn(const Reader& r, const json& v, const std::string& field, double lo, double hi,
                bool lo_open = false) {
  if (!v.is_number()) r.Fail(field, "must be a number");
  const double x = v.get<double>();
  const bool above = lo_open ? x > lo : x >= lo;
  if (!std::isfinite(x) || !above || !(x <= hi)) {
    std::ostringstream range;
    range << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
    r.Fail(field, "must be in " + range.str());
  }
  return x;
}

int64_t Integer(const Reader& r, const json& v, const std::string& field, int64_t lo, int64_t hi) {
  if (!v.is_number_integer()) r.Fail(field, "must be an integer");
  const bool too_large = v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(hi);
  const int64_t x = too_large ? hi : v.get<int64_t>();
  if (too_large || x < lo || x > hi) {
    r.Fail(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return x;
}

std::string String(const Reader& r, const json& v, const std::string& field) {
  if (!v.is_string()) r.Fail(field, "must be a string");
  return v.get<std::string>();
}

const json& ObjectAt(const Reader& r, const json& v, const std::string& field) {
  if (!v.is_object()) r.Fail(field, "must be an object");
  return v;
}

WashoutEdit ParseWashout(const Reader& r, const json& j, const std::string& field) {
  ObjectAt(r, j, field);
  CheckKeys(r, j, field, {"mode", "return_accel_m_s2", "window_s", "tau_s", "order"});
  WashoutEdit w;
  if (j.contains("mode")) {
    w.mode = String(r, j["mode"], field + ".mode");
    if (*w.mode != "adaptive" && *w.mode != "highpass" && *w.mode != "off") {
      r.Fail(field + ".mode", "'" + Shown(*w.mode) + "' is not adaptive, highpass or off");
    }
  }
  // The ranges of WashoutOptions::Check.
  if (j.contains("return_accel_m_s2")) {
    w.return_accel_m_s2 =
        NumberIn(r, j["return_accel_m_s2"], field + ".return_accel_m_s2", 0, 100, true);
  }
  if (j.contains("window_s")) w.window_s = NumberIn(r, j["window_s"], field + ".window_s", 0, 3600, true);
  if (j.contains("tau_s")) w.tau_s = NumberIn(r, j["tau_s"], field + ".tau_s", 0.05, 600, true);
  if (j.contains("order")) w.order = static_cast<int>(Integer(r, j["order"], field + ".order", 1, 2));
  return w;
}

ShotEdit ParseShot(const Reader& r, const json& j, const std::string& field) {
  ObjectAt(r, j, field);
  CheckKeys(r, j, field, {"shot", "model", "gain", "mute", "washout"});
  if (!j.contains("shot")) r.Fail(field, "missing \"shot\" (the camera path's shot number)");
  ShotEdit s;
  s.shot = static_cast<int>(Integer(r, j["shot"], field + ".shot", std::numeric_limits<int>::min(),
                                    std::numeric_limits<int>::max()));
  if (j.contains("model")) {
    const std::string name = String(r, j["model"], field + ".model");
    try {
      s.model = HapticModelFromName(name);
    } catch (const UsageError&) {
      r.Fail(field + ".model", "'" + Shown(name) + "' is not cinematic, semantic, random or none");
    }
  }
  if (j.contains("gain")) s.gain = NumberIn(r, j["gain"], field + ".gain", 0, kMaxShotGain);
  if (j.contains("mute")) {
    if (!j["mute"].is_boolean()) r.Fail(field + ".mute", "must be true or false");
    s.mute = j["mute"].get<bool>();
  }
  if (j.contains("washout")) s.washout = ParseWashout(r, j["washout"], field + ".washout");
  return s;
}

std::vector<ShotEdit> ParseShots(const Reader& r, const json& j) {
  if (!j.is_array()) r.Fail("shots", "must be a list");
  std::vector<ShotEdit> shots;
  for (size_t i = 0; i < j.size(); ++i) {
    shots.push_back(ParseShot(r, j[i], "shots[" + std::to_string(i) + "]"));
  }
  std::stable_sort(shots.begin(), shots.end(),
                   [](const ShotEdit& a, const ShotEdit& b) { return a.shot < b.shot; });
  for (size_t i = 1; i < shots.size(); ++i) {
    if (shots[i].shot == shots[i - 1].shot) {
      r.Fail("shots", "shot " + std::to_string(shots[i].shot) + " is listed twice");
    }
  }
  return shots;
}

EffectSegment ParseKeyframe(const Reader& r, const json& j, const std::string& field) {
  ObjectAt(r, j, field);
  CheckKeys(r, j, field, {"start_s", "end_s", "effect", "intensity"});
  for (const char* key : {"start_s", "end_s", "effect"}) {
    if (!j.contains(key)) r.Fail(field, std::string("missing \"") + key + "\"");
  }
  EffectSegment s;
  s.start_s = NumberIn(r, j["start_s"], field + ".start_s", 0, 1e8);
  s.end_s = NumberIn(r, j["end_s"], field + ".end_s", 0, 1e8);
  if (!(s.end_s > s.start_s)) r.Fail(field + ".end_s", "must be after start_s");
  const std::string name = String(r, j["effect"], field + ".effect");
  const std::optional<CameraEffect> effect = EffectFromName(name);
  if (!effect || *effect == CameraEffect::kNone) {
    r.Fail(field + ".effect", "unknown effect '" + Shown(name) + "' (a Table 1 or Table 2 name)");
  }
  s.effect = *effect;
  if (j.contains("intensity")) s.intensity = NumberIn(r, j["intensity"], field + ".intensity", -1, 1);
  return s;
}

std::vector<EffectSegment> ParseKeyframeList(const Reader& r, const json& j) {
  if (!j.is_array()) r.Fail("keyframes", "must be a list");
  std::vector<EffectSegment> segs;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string field = "keyframes[" + std::to_string(i) + "]";
    segs.push_back(ParseKeyframe(r, j[i], field));
    if (i > 0 && segs[i].start_s < segs[i - 1].end_s) {
      r.Fail(field + ".start_s", "starts before the previous keyframe ends (keep them in time "
                                 "order, without overlap)");
    }
  }
  try {
    CheckSegments(segs);  // the semantic model's own rule, should the two ever differ
  } catch (const UsageError& e) {
    r.Fail("keyframes", e.what());
  }
  return segs;
}

json ParseJsonText(const std::string& text, const std::string& source) {
  if (text.size() > kMaxEditsFileBytes) throw Error(source, "larger than 4 MiB");
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw Error(source, "not valid JSON: " + what);
  }
}

void CheckHeader(const Reader& r, const json& j) {
  if (!j.contains("format")) r.Fail("format", "missing (must be \"hapcine-edits\")");
  if (!j["format"].is_string() || j["format"].get<std::string>() != kFormatName) {
    r.Fail("format", "must be \"hapcine-edits\" (is this an edits file?)");
  }
  if (!j.contains("version")) r.Fail("version", "missing (must be 1)");
  if (!j["version"].is_number_integer() || j["version"].get<int64_t>() != kFormatVersion) {
    r.Fail("version", Shown(j["version"].dump()) + " is not supported (this hapcine reads version 1)");
  }
}

}  // namespace

bool WashoutEdit::operator==(const WashoutEdit& o) const {
  return mode == o.mode && return_accel_m_s2 == o.return_accel_m_s2 && window_s == o.window_s &&
         tau_s == o.tau_s && order == o.order;
}

bool ShotEdit::operator==(const ShotEdit& o) const {
  return shot == o.shot && model == o.model && gain == o.gain && mute == o.mute &&
         washout == o.washout;
}

const ShotEdit* HapticEdits::FindShot(int shot) const {
  // A scan, not a binary search: edits built in code need not be sorted.
  auto it = std::find_if(shots.begin(), shots.end(), [&](const ShotEdit& s) { return s.shot == shot; });
  return it != shots.end() ? &*it : nullptr;
}

bool HapticEdits::operator==(const HapticEdits& o) const {
  auto same_segments = [](const std::vector<EffectSegment>& a,
                          const std::vector<EffectSegment>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const EffectSegment& x, const EffectSegment& y) {
                        return x.start_s == y.start_s && x.end_s == y.end_s &&
                               x.effect == y.effect && x.intensity == y.intensity;
                      });
  };
  if (keyframes.has_value() != o.keyframes.has_value()) return false;
  if (keyframes && !same_segments(*keyframes, *o.keyframes)) return false;
  return revision == o.revision && shots == o.shots && extensions == o.extensions;
}

HapticEdits ParseHapticEdits(const std::string& text, const std::string& source) {
  const Reader r{source};
  const json j = ParseJsonText(text, source);
  if (!j.is_object()) throw Error(source, "an edits file is a JSON object");
  CheckHeader(r, j);
  CheckKeys(r, j, "", {"format", "version", "revision", "shots", "keyframes"});
  HapticEdits edits;
  if (j.contains("revision")) {
    edits.revision = Integer(r, j["revision"], "revision", 0, std::numeric_limits<int64_t>::max());
  }
  if (j.contains("shots")) edits.shots = ParseShots(r, j["shots"]);
  if (j.contains("keyframes")) edits.keyframes = ParseKeyframeList(r, j["keyframes"]);
  for (const auto& item : j.items()) {
    if (IsExtensionKey(item.key())) edits.extensions[item.key()] = item.value().dump();
  }
  return edits;
}

namespace {

ordered_json ShotToJson(const ShotEdit& s) {
  ordered_json j;
  j["shot"] = s.shot;
  if (s.model) j["model"] = HapticModelName(*s.model);
  if (s.gain) j["gain"] = *s.gain;
  if (s.mute) j["mute"] = *s.mute;
  if (s.washout) {
    ordered_json w = ordered_json::object();
    if (s.washout->mode) w["mode"] = *s.washout->mode;
    if (s.washout->return_accel_m_s2) w["return_accel_m_s2"] = *s.washout->return_accel_m_s2;
    if (s.washout->window_s) w["window_s"] = *s.washout->window_s;
    if (s.washout->tau_s) w["tau_s"] = *s.washout->tau_s;
    if (s.washout->order) w["order"] = *s.washout->order;
    j["washout"] = w;
  }
  return j;
}

}  // namespace

std::string HapticEditsToJson(const HapticEdits& edits) {
  ordered_json j;
  j["format"] = kFormatName;
  j["version"] = kFormatVersion;
  j["revision"] = edits.revision;
  if (!edits.shots.empty()) {
    ordered_json shots = ordered_json::array();
    for (const ShotEdit& s : edits.shots) shots.push_back(ShotToJson(s));
    j["shots"] = shots;
  }
  if (edits.keyframes) {
    ordered_json keys = ordered_json::array();
    for (const EffectSegment& s : *edits.keyframes) {
      keys.push_back({{"start_s", s.start_s},
                      {"end_s", s.end_s},
                      {"effect", EffectName(s.effect)},
                      {"intensity", s.intensity}});
    }
    j["keyframes"] = keys;
  }
  for (const auto& [key, text] : edits.extensions) j[key] = ordered_json::parse(text);
  return j.dump(2) + "\n";
}

HapticEdits ReadHapticEditsFile(const std::string& path) {
  CheckRegularFile(path);
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxEditsFileBytes) throw Error(path, "larger than 4 MiB");
  InputFile in(path, std::ios::in | std::ios::binary);
  std::string text(kMaxEditsFileBytes + 1, '\0');
  in.stream().read(&text[0], static_cast<std::streamsize>(text.size()));
  if (in.stream().bad()) throw Error(path, "read error");
  text.resize(static_cast<size_t>(in.stream().gcount()));
  return ParseHapticEdits(text, path);
}

void WriteHapticEditsFile(const HapticEdits& edits, const std::string& path) {
  const std::string text = HapticEditsToJson(edits);
  AtomicFile file(path);
  file.stream() << text;
  file.Commit();
}

std::string EditsPathForFilm(const std::string& film_or_camera_path) {
  const fs::path p(film_or_camera_path);
  const std::string name = p.filename().string();
  const std::string camera_suffix = ".camera.csv";
  std::string stem;
  if (name.size() > camera_suffix.size() &&
      name.compare(name.size() - camera_suffix.size(), camera_suffix.size(), camera_suffix) == 0) {
    stem = name.substr(0, name.size() - camera_suffix.size());
  } else {
    stem = p.stem().string();
  }
  return (p.parent_path() / (stem + ".edits.json")).string();
}

}  // namespace hapcine
