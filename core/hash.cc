#include "core/hash.h"

#include <cstdio>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine {

void Fnv1a64::Update(const void* data, size_t size_bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t h = hash_;
  for (size_t i = 0; i < size_bytes; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;  // FNV prime
  }
  hash_ = h;
}

std::string Fnv1a64::Hex() const {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(hash_));
  return buf;
}

std::string Fnv1a64Hex(const std::string& s) {
  Fnv1a64 h;
  h.Update(s);
  return h.Hex();
}

std::string Fnv1a64FileHex(const std::string& path) {
  InputFile file(path, std::ios::binary);  // regular files only: a FIFO would block
  std::ifstream& in = file.stream();
  Fnv1a64 h;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h.Update(buf.data(), static_cast<size_t>(in.gcount()));
  }
  if (in.bad()) throw Error(path, "read error while hashing");
  return h.Hex();
}

}  // namespace hapcine
