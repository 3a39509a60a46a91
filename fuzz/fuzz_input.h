#pragma once
// Shared by the fuzz targets. The contract every reader is held to: on any
// input it returns, or throws hapcine::Error (one line naming the file and
// the reason). Any other exception (std::bad_alloc, std::out_of_range,
// nlohmann's), a crash, a sanitizer report or a hang is a bug, and libFuzzer
// reports it.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace hapcine::fuzz {

inline std::string AsString(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs `read`; an Error is the expected way to refuse an input.
template <class Read>
void AcceptOnlyError(Read&& read) {
  try {
    read();
  } catch (const Error&) {
  }
}

// One private directory per process for readers that take only a path:
// created on first use, removed at exit. The removal is registered after the
// path is made: exit runs it before the path's destructor (the reverse order
// of registration), so it still sees the path.
inline std::filesystem::path MakeScratchDir() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/hapcine-fuzz-XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (!mkdtemp(buf.data())) {
    std::perror("hapcine fuzz: mkdtemp");
    std::abort();
  }
  return std::filesystem::path(buf.data());
}

inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = MakeScratchDir();
  static const bool removed_at_exit = [] {
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(ScratchDir(), ignored);
    });
    return true;
  }();
  (void)removed_at_exit;
  return dir;
}

// Writes `text` to ScratchDir()/name (replacing it) and returns the path.
inline std::string WriteScratchFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) {
    std::perror("hapcine fuzz: writing the scratch file");
    std::abort();
  }
  return path.string();
}

}  // namespace hapcine::fuzz
