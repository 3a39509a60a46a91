#pragma once
// Content hashes for the study files: 64-bit FNV-1a, printed as 16 hex digits.
// Not cryptographic — it detects accidental change (a re-rendered haptic
// track, an edited plan), which is all a study needs: results are only
// comparable if every participant saw exactly the same stimuli.

#include <cstdint>
#include <string>

namespace hapcine::study {

uint64_t Fnv1a64(const std::string& bytes, uint64_t h = 0xcbf29ce484222325ULL);
std::string HexDigest(uint64_t h);
// Hash of a file's bytes; throws hapcine::Error naming the file if unreadable.
std::string HashFile(const std::string& path);
std::string HashString(const std::string& bytes);

}  // namespace hapcine::study
