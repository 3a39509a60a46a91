#include "haptics/keyframes.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/csv.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/text.h"

namespace hapcine {
namespace {

double ParseNumber(const std::string& text, const std::string& where, const char* name) {
  const std::string t = TrimBlanks(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || !std::isfinite(v)) {
    throw Error(where, std::string("bad ") + name + " '" + t + "'");
  }
  return v;
}

}  // namespace

std::vector<EffectSegment> ReadKeyframes(std::istream& in, const std::string& src) {
  std::vector<EffectSegment> segs;
  std::string line;
  int line_no = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = TrimBlanks(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = src + ":" + std::to_string(line_no);
    std::vector<std::string> f = SplitCsvLine(t);
    for (auto& s : f) s = TrimBlanks(s);
    if (!have_header) {
      if (f != std::vector<std::string>{"start_s", "end_s", "effect", "intensity"}) {
        throw Error(where, "header must be 'start_s,end_s,effect,intensity'");
      }
      have_header = true;
      continue;
    }
    if (f.size() != 4) {
      throw Error(where, "expected 4 fields, got " + std::to_string(f.size()));
    }
    EffectSegment s;
    s.start_s = ParseNumber(f[0], where, "start_s");
    s.end_s = ParseNumber(f[1], where, "end_s");
    const auto effect = EffectFromName(f[2]);
    if (!effect || *effect == CameraEffect::kNone)
      throw Error(where, "unknown effect '" + f[2] + "'");
    s.effect = *effect;
    s.intensity = ParseNumber(f[3], where, "intensity");
    if (s.start_s < 0) throw Error(where, "start_s is negative");
    if (!(s.end_s > s.start_s)) throw Error(where, "end_s must be after start_s");
    if (!(std::abs(s.intensity) <= 1)) throw Error(where, "intensity outside [-1, 1]");
    if (!segs.empty() && s.start_s < segs.back().end_s) {
      throw Error(where,
                  "segment starts before the previous one ends (keep them in time order, "
                  "without overlap)");
    }
    segs.push_back(s);
  }
  if (!have_header) throw Error(src, "empty keyframe file (no header)");
  return segs;
}

std::vector<EffectSegment> ReadKeyframesFile(const std::string& path) {
  InputFile in(path);
  return ReadKeyframes(in.stream(), path);
}

void WriteKeyframes(const std::vector<EffectSegment>& segs, std::ostream& out) {
  out << JoinCsvLine({"start_s", "end_s", "effect", "intensity"}) << "\n";
  for (const auto& s : segs) {
    out << JoinCsvLine({FormatDouble(s.start_s), FormatDouble(s.end_s), EffectName(s.effect),
                        FormatDouble(s.intensity)})
        << "\n";
  }
}

}  // namespace hapcine
