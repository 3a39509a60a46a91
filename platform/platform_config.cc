#include "platform/platform_config.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/rotation.h"
#include "platform/stewart.h"

namespace hapcine {
namespace {

using nlohmann::json;

const char* const kDofNames[kNumDofs] = {"sway", "heave", "surge", "pitch", "yaw", "roll"};

double ReadNum(const json& j, const std::string& key, const std::string& src) {
  if (!j.is_number()) throw Error(src, "'" + key + "' must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw Error(src, "'" + key + "' is not finite");
  return v;
}

Eigen::Vector3d ReadVec(const json& j, const std::string& key, const std::string& src) {
  if (!j.is_array() || j.size() != 3)
    throw Error(src, "'" + key + "' must hold arrays of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = ReadNum(j[i], key, src);
  return v;
}

std::array<Eigen::Vector3d, 6> ReadAnchors(const json& j, const std::string& key,
                                           const std::string& src) {
  if (!j.is_array() || j.size() != 6) throw Error(src, "'" + key + "' must hold 6 points");
  std::array<Eigen::Vector3d, 6> out;
  for (int i = 0; i < 6; ++i) out[i] = ReadVec(j[i], key, src);
  return out;
}

int DofIndex(const std::string& name) {
  for (int d = 0; d < kNumDofs; ++d) {
    if (name == kDofNames[d]) return d;
  }
  return -1;
}

// Degrees in the file for rotations, SI inside.
double ToSi(int dof, double v) { return IsRotation(dof) ? DegToRad(v) : v; }
double FromSi(int dof, double v) { return IsRotation(dof) ? RadToDeg(v) : v; }

DofLimits ReadLimits(const json& j, int dof, const std::string& src) {
  const std::string where = std::string("dofs.") + kDofNames[dof];
  if (!j.is_object()) throw Error(src, "'" + where + "' must be an object");
  DofLimits l;
  bool seen[3] = {false, false, false};
  for (auto it = j.begin(); it != j.end(); ++it) {
    const double v = ToSi(dof, ReadNum(*it, where + "." + it.key(), src));
    if (it.key() == "position") l.position = v, seen[0] = true;
    else if (it.key() == "velocity") l.velocity = v, seen[1] = true;
    else if (it.key() == "acceleration") l.acceleration = v, seen[2] = true;
    else throw Error(src, "unknown key '" + where + "." + it.key() + "'");
  }
  if (!(seen[0] && seen[1] && seen[2]))
    throw Error(src, "'" + where + "' needs position, velocity and acceleration");
  return l;
}

StewartGeometry ReadStewart(const json& j, const std::string& src) {
  if (!j.is_object()) throw Error(src, "'stewart' must be an object");
  StewartGeometry g;
  int seen = 0;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    if (k == "base_anchors_m") g.base_m = ReadAnchors(*it, k, src), seen |= 1;
    else if (k == "top_anchors_m") g.top_m = ReadAnchors(*it, k, src), seen |= 2;
    else if (k == "min_leg_m") g.min_leg_m = ReadNum(*it, k, src), seen |= 4;
    else if (k == "max_leg_m") g.max_leg_m = ReadNum(*it, k, src), seen |= 8;
    else if (k != "comment") throw Error(src, "unknown key 'stewart." + k + "'");
  }
  if (seen != 15)
    throw Error(src, "'stewart' needs base_anchors_m, top_anchors_m, min_leg_m and max_leg_m");
  return g;
}

// (JSON key, field, is an angle) of the cueing parameters.
struct CueingKey {
  const char* key;
  double CueingParams::*field;
  bool degrees;
};
const CueingKey kCueingKeys[] = {
    {"usable_fraction", &CueingParams::usable_fraction, false},
    {"fill_motion_u", &CueingParams::fill_motion_u, false},
    {"return_accel_m_s2", &CueingParams::return_accel_m_s2, false},
    {"return_speed_m_s", &CueingParams::return_speed_m_s, false},
    {"return_rate_deg_s", &CueingParams::return_rate_rad_s, true},
    {"return_accel_deg_s2", &CueingParams::return_accel_rad_s2, true},
    {"tilt_max_deg", &CueingParams::tilt_max_rad, true},
    {"tilt_rate_deg_s", &CueingParams::tilt_rate_rad_s, true},
    {"tilt_lowpass_s", &CueingParams::tilt_lowpass_s, false},
    {"specific_force_gain", &CueingParams::specific_force_gain, false},
    {"cut_ramp_s", &CueingParams::cut_ramp_s, false},
    {"still_speed_m_s", &CueingParams::still_speed_m_s, false},
    {"still_rate_deg_s", &CueingParams::still_rate_rad_s, true},
};

void ReadCueing(const json& j, const std::string& src, CueingParams* c) {
  if (!j.is_object()) throw Error(src, "'cueing' must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = it.key() == "comment";
    for (const CueingKey& k : kCueingKeys) {
      if (it.key() != k.key) continue;
      const double v = ReadNum(*it, std::string("cueing.") + k.key, src);
      c->*k.field = k.degrees ? DegToRad(v) : v;
      known = true;
    }
    if (!known) throw Error(src, "unknown key 'cueing." + it.key() + "'");
  }
}

void ReadTopLevelKey(const json::const_iterator& it, const std::string& src, PlatformConfig* c) {
  const std::string& k = it.key();
  if (k == "type" || k == "comment") return;
  if (k == "name") {
    if (!it->is_string()) throw Error(src, "'name' must be a string");
    c->name = it->get<std::string>();
  } else if (k == "rate_hz") {
    c->rate_hz = ReadNum(*it, k, src);
  } else if (k == "dofs") {
    if (!it->is_object()) throw Error(src, "'dofs' must be an object");
    for (auto d = it->begin(); d != it->end(); ++d) {
      const int dof = DofIndex(d.key());
      if (dof < 0) throw Error(src, "unknown degree of freedom '" + d.key() +
                                        "' (sway, heave, surge, pitch, yaw, roll)");
      c->enabled[dof] = true;
      c->limits[dof] = ReadLimits(*d, dof, src);
    }
  } else if (k == "stewart") {
    c->stewart = ReadStewart(*it, src);
  } else if (k == "cueing") {
    ReadCueing(*it, src, &c->cueing);
  } else {
    throw Error(src, "unknown key '" + k + "'");
  }
}

bool InRange(double v, double lo, double hi) { return v >= lo && v <= hi; }

}  // namespace

const char* DofName(Dof d) { return kDofNames[static_cast<int>(d)]; }

int PlatformConfig::NumEnabled() const {
  int n = 0;
  for (bool e : enabled) n += e;
  return n;
}

void CueingParams::Check() const {
  if (!InRange(usable_fraction, 0.1, 1)) throw UsageError("cueing: usable_fraction must be in [0.1, 1]");
  if (!InRange(fill_motion_u, 1e-6, 1e6)) throw UsageError("cueing: fill_motion_u must be in [1e-6, 1e6]");
  for (double v : {return_accel_m_s2, return_speed_m_s, return_rate_rad_s, return_accel_rad_s2,
                   tilt_rate_rad_s, tilt_lowpass_s, still_speed_m_s, still_rate_rad_s}) {
    if (!InRange(v, 1e-9, 100)) throw UsageError("cueing: rates, thresholds and time constants must be in (0, 100]");
  }
  if (!InRange(tilt_max_rad, 0, DegToRad(30))) throw UsageError("cueing: tilt_max_deg must be in [0, 30]");
  if (!InRange(specific_force_gain, 0, 1e3)) throw UsageError("cueing: specific_force_gain must be in [0, 1000]");
  if (!InRange(cut_ramp_s, 0, 10)) throw UsageError("cueing: cut_ramp_s must be in [0, 10]");
}

void PlatformConfig::Check() const {
  if (NumEnabled() == 0) throw UsageError("platform: 'dofs' names no degree of freedom");
  if (!InRange(rate_hz, 10, 10000)) throw UsageError("platform: rate_hz must be in [10, 10000]");
  for (int d = 0; d < kNumDofs; ++d) {
    if (!enabled[d]) continue;
    const DofLimits& l = limits[d];
    const double max_pos = IsRotation(d) ? DegToRad(60) : 1.0;
    if (!(InRange(l.position, 1e-6, max_pos) && InRange(l.velocity, 1e-6, 100) &&
          InRange(l.acceleration, 1e-6, 1000))) {
      throw UsageError(std::string("platform: limits of ") + kDofNames[d] +
                       " must be > 0, position <= 1 m or 60 deg, velocity <= 100, "
                       "acceleration <= 1000 (per second, degrees for rotations)");
    }
  }
  cueing.Check();
  if (stewart) {
    const StewartGeometry& g = *stewart;
    if (!(g.min_leg_m > 0 && g.min_leg_m < g.max_leg_m && g.max_leg_m <= 10))
      throw UsageError("platform: stewart needs 0 < min_leg_m < max_leg_m <= 10");
    const double margin = 0.5 * (1 - cueing.usable_fraction) * (g.max_leg_m - g.min_leg_m);
    if (!LegsWithinStroke(g, StewartLegLengths(g, PlatformPose::Zero()), margin))
      throw UsageError("platform: stewart legs at the home pose are outside the usable stroke");
  }
}

bool IsPlatformJson(const std::string& text) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return false;
  const auto it = j.find("type");
  return it != j.end() && it->is_string() && it->get<std::string>() == "platform";
}

bool IsPlatformFile(const std::string& path) {
  try {
    InputFile in(path);
    std::stringstream ss;
    ss << in.stream().rdbuf();
    return IsPlatformJson(ss.str());
  } catch (const std::exception&) {
    return false;
  }
}

PlatformConfig ParsePlatformJson(const std::string& text, const std::string& src) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(src, std::string("not valid JSON: ") + e.what());
  }
  if (!IsPlatformJson(text)) throw Error(src, "a platform file needs \"type\": \"platform\"");
  PlatformConfig c;
  for (auto it = j.cbegin(); it != j.cend(); ++it) ReadTopLevelKey(it, src, &c);
  try {
    c.Check();
  } catch (const UsageError& e) {
    throw Error(src, e.what());
  }
  return c;
}

PlatformConfig LoadPlatformFile(const std::string& path) {
  InputFile in(path);
  std::stringstream ss;
  ss << in.stream().rdbuf();
  return ParsePlatformJson(ss.str(), path);
}

std::string PlatformConfigToJson(const PlatformConfig& c) {
  json j;
  j["type"] = "platform";
  j["name"] = c.name;
  j["rate_hz"] = c.rate_hz;
  json dofs = json::object();
  for (int d = 0; d < kNumDofs; ++d) {
    if (!c.enabled[d]) continue;
    dofs[kDofNames[d]] = {{"position", FromSi(d, c.limits[d].position)},
                          {"velocity", FromSi(d, c.limits[d].velocity)},
                          {"acceleration", FromSi(d, c.limits[d].acceleration)}};
  }
  j["dofs"] = dofs;
  json cue = json::object();
  for (const CueingKey& k : kCueingKeys) {
    cue[k.key] = k.degrees ? RadToDeg(c.cueing.*k.field) : c.cueing.*k.field;
  }
  j["cueing"] = cue;
  if (c.stewart) {
    auto points = [](const std::array<Eigen::Vector3d, 6>& a) {
      json out = json::array();
      for (const auto& p : a) out.push_back({p.x(), p.y(), p.z()});
      return out;
    };
    j["stewart"] = {{"base_anchors_m", points(c.stewart->base_m)},
                    {"top_anchors_m", points(c.stewart->top_m)},
                    {"min_leg_m", c.stewart->min_leg_m},
                    {"max_leg_m", c.stewart->max_leg_m}};
  }
  return j.dump(2) + "\n";
}

}  // namespace hapcine
