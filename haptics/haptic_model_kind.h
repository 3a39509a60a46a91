#pragma once
// The four haptic models by name; MakeHapticTrack (haptic_models.h) runs them
// and an edits file (haptic_edits.h) can choose one per shot.

#include <string>

namespace hapcine {

enum class HapticModel { kCinematic, kSemantic, kRandom, kNone };
const char* HapticModelName(HapticModel m);  // "cinematic", "semantic", "random", "none"
HapticModel HapticModelFromName(const std::string& name);  // throws UsageError

}  // namespace hapcine
