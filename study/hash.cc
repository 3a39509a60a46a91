#include "study/hash.h"

#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine::study {

uint64_t Fnv1a64(const std::string& bytes, uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string HexDigest(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string HashString(const std::string& bytes) { return HexDigest(Fnv1a64(bytes)); }

std::string HashFile(const std::string& path) {
  InputFile file(path, std::ios::binary);
  std::ifstream& in = file.stream();
  uint64_t h = 0xcbf29ce484222325ULL;
  std::string buf(1 << 16, '\0');
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize got = in.gcount();
    if (got > 0) h = Fnv1a64(buf.substr(0, static_cast<size_t>(got)), h);
  }
  if (in.bad()) throw Error(path, "read error while hashing");
  return HexDigest(h);
}

}  // namespace hapcine::study
