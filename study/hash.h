#pragma once
// Content hashes for the study files: FNV-1a 64 (core/hash.h), printed as 16
// hex digits. It detects accidental change (a re-rendered haptic track, an
// edited plan), which is all a study needs: results are only comparable if
// every participant saw exactly the same stimuli.

#include <string>

namespace hapcine::study {

// Hash of a file's bytes; throws hapcine::Error naming the file if unreadable.
std::string HashFile(const std::string& path);
std::string HashString(const std::string& bytes);

}  // namespace hapcine::study
