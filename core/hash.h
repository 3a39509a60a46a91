#pragma once
// FNV-1a 64: the project's content hash (batch film identities and settings,
// study stimuli and plans). Not cryptographic: it detects accidental change
// (a re-encoded film, a re-rendered track), needs no library and gives the
// same value on every platform.

#include <cstddef>
#include <cstdint>
#include <string>

namespace hapcine {

// Incremental FNV-1a 64-bit hash.
class Fnv1a64 {
 public:
  void Update(const void* data, size_t size_bytes);
  void Update(const std::string& s) { Update(s.data(), s.size()); }
  uint64_t value() const { return hash_; }
  std::string Hex() const;  // 16 lower-case hex digits

 private:
  uint64_t hash_ = 14695981039346656037ull;  // offset basis
};

// Hex() of the hash of `s`.
std::string Fnv1a64Hex(const std::string& s);

// Hex() of the hash of a file's bytes; throws hapcine::Error(path, reason)
// when it cannot be opened or read.
std::string Fnv1a64FileHex(const std::string& path);

}  // namespace hapcine
