#include "batch/content_hash.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine::batch {
namespace {

constexpr uint64_t kWindowBytes = 1 << 20;  // 1 MiB

struct FileCloser {
  void operator()(FILE* f) const {
    if (f) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<FILE, FileCloser>;

FilePtr OpenOrThrow(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  return f;
}

// Also refuses what is not a regular file: opening a FIFO would block the
// whole batch before any film runs.
uint64_t SizeOrThrow(const std::string& path) {
  CheckRegularFile(path);
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    throw Error(path, std::string("cannot stat: ") + std::strerror(errno));
  }
  return static_cast<uint64_t>(st.st_size);
}

// Hashes [offset, offset + length) of f.
void HashRange(FILE* f, const std::string& path, uint64_t offset, uint64_t length, Fnv1a64* hash) {
  if (fseeko(f, static_cast<off_t>(offset), SEEK_SET) != 0) {
    throw Error(path, std::string("cannot seek: ") + std::strerror(errno));
  }
  std::vector<char> buf(64 * 1024);
  while (length > 0) {
    const size_t want = static_cast<size_t>(std::min<uint64_t>(length, buf.size()));
    const size_t got = std::fread(buf.data(), 1, want, f);
    if (got == 0) {
      if (std::ferror(f)) throw Error(path, "read error");
      break;  // file shrank while reading: hash what is there
    }
    hash->Update(buf.data(), got);
    length -= got;
  }
}

}  // namespace

ContentId SampledContentId(const std::string& path) {
  ContentId id;
  id.size_bytes = SizeOrThrow(path);
  FilePtr f = OpenOrThrow(path);
  Fnv1a64 hash;
  const uint64_t size = id.size_bytes;
  hash.Update(&size, sizeof(size));  // little-endian on every target we build for
  if (size <= 3 * kWindowBytes) {
    HashRange(f.get(), path, 0, size, &hash);
  } else {
    HashRange(f.get(), path, 0, kWindowBytes, &hash);
    HashRange(f.get(), path, size / 2 - kWindowBytes / 2, kWindowBytes, &hash);
    HashRange(f.get(), path, size - kWindowBytes, kWindowBytes, &hash);
  }
  id.hash = "fnv1a64s:" + hash.Hex();
  return id;
}

std::string FullFileHash(const std::string& path) {
  const uint64_t size = SizeOrThrow(path);
  FilePtr f = OpenOrThrow(path);
  Fnv1a64 hash;
  HashRange(f.get(), path, 0, size, &hash);
  return "fnv1a64:" + hash.Hex();
}

bool FilesEqual(const std::string& a, const std::string& b) {
  if (SizeOrThrow(a) != SizeOrThrow(b)) return false;
  FilePtr fa = OpenOrThrow(a);
  FilePtr fb = OpenOrThrow(b);
  std::vector<char> ba(64 * 1024), bb(64 * 1024);
  while (true) {
    const size_t na = std::fread(ba.data(), 1, ba.size(), fa.get());
    const size_t nb = std::fread(bb.data(), 1, bb.size(), fb.get());
    if (na != nb) return false;
    if (na == 0) return !std::ferror(fa.get()) && !std::ferror(fb.get());
    if (std::memcmp(ba.data(), bb.data(), na) != 0) return false;
  }
}

}  // namespace hapcine::batch
