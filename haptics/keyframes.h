#pragma once
// Hand-placed semantic effects (the paper's "home-made editor"): a small CSV
// file, one effect segment per line.
//
//   # comments and blank lines are ignored
//   start_s,end_s,effect,intensity
//   1.0,6.0,dutch_angle,1
//   8.5,12,crab_walk,-0.6
//
// effect: a Table 1 name (crane_shot, dutch_angle, arcing, traveling,
// tilting, zoom_in, vertigo) or its Table 2 metaphor (flying_away,
// instability, intensification, crab_walk, inferiority, walk_forward,
// vertigo). intensity in [-1, 1] (sign mirrors the direction). Segments must
// be in time order and must not overlap. Any violation throws
// Error("<file>:<line>", reason).

#include <istream>
#include <string>
#include <vector>

#include "haptics/semantic_model.h"

namespace hapcine {

std::vector<EffectSegment> ReadKeyframes(std::istream& in, const std::string& source_name);
std::vector<EffectSegment> ReadKeyframesFile(const std::string& path);
void WriteKeyframes(const std::vector<EffectSegment>& segments, std::ostream& out);

}  // namespace hapcine
