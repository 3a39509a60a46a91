#include "study/json_util.h"

#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine::study {

using nlohmann::json;

json ReadJsonFile(const std::string& path) {
  InputFile in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.stream().rdbuf();
  try {
    return json::parse(ss.str());
  } catch (const json::exception& e) {
    std::string what = e.what();
    // nlohmann prefixes "[json.exception.parse_error.101] "; keep the reason.
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw Error(path, "not valid JSON: " + what);
  }
}

const json& Field(const json& j, const std::string& key, const std::string& source,
                  const std::string& where) {
  if (!j.is_object()) throw Error(source, where + " is not a JSON object");
  const auto it = j.find(key);
  if (it == j.end()) throw Error(source, where + ": missing field '" + key + "'");
  return *it;
}

std::string StringField(const json& j, const std::string& key, const std::string& source,
                        const std::string& where) {
  const json& v = Field(j, key, source, where);
  if (!v.is_string()) throw Error(source, where + ": field '" + key + "' is not a string");
  return v.get<std::string>();
}

double NumberField(const json& j, const std::string& key, const std::string& source,
                   const std::string& where) {
  const json& v = Field(j, key, source, where);
  if (!v.is_number()) throw Error(source, where + ": field '" + key + "' is not a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw Error(source, where + ": field '" + key + "' is not finite");
  return d;
}

int IntField(const json& j, const std::string& key, const std::string& source,
             const std::string& where) {
  const json& v = Field(j, key, source, where);
  if (!v.is_number_integer())
    throw Error(source, where + ": field '" + key + "' is not an integer");
  const auto i = v.get<int64_t>();
  if (i < -1000000000LL || i > 1000000000LL)
    throw Error(source, where + ": field '" + key + "' out of range");
  return static_cast<int>(i);
}

uint64_t Uint64Field(const json& j, const std::string& key, const std::string& source,
                     const std::string& where) {
  const json& v = Field(j, key, source, where);
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
    throw Error(source, where + ": field '" + key + "' is not a non-negative integer");
  return v.get<uint64_t>();
}

const json& ArrayField(const json& j, const std::string& key, const std::string& source,
                       const std::string& where) {
  const json& v = Field(j, key, source, where);
  if (!v.is_array()) throw Error(source, where + ": field '" + key + "' is not an array");
  return v;
}

std::vector<std::string> StringArray(const json& j, const std::string& source,
                                     const std::string& where) {
  if (!j.is_array()) throw Error(source, where + " is not an array");
  std::vector<std::string> out;
  for (const auto& e : j) {
    if (!e.is_string()) throw Error(source, where + " holds a non-string");
    out.push_back(e.get<std::string>());
  }
  return out;
}

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace hapcine::study
