#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace hapcine {

std::string TempPathFor(const std::string& final_path) {
  return final_path + ".tmp-" + std::to_string(::getpid());
}

void CommitTempFile(const std::string& temp_path,
                    const std::string& final_path) {
  int fd = ::open(temp_path.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);  // data on disk before the name points at it
    ::close(fd);
  }
  if (std::rename(temp_path.c_str(), final_path.c_str()) != 0) {
    std::string reason = std::string("cannot rename temporary file: ") +
                         std::strerror(errno);
    RemoveTempFile(temp_path);
    throw Error(final_path, reason);
  }
}

void RemoveTempFile(const std::string& temp_path) noexcept {
  std::remove(temp_path.c_str());
}

AtomicFile::AtomicFile(const std::string& path)
    : path_(path), temp_path_(TempPathFor(path)) {
  out_.open(temp_path_, std::ios::out | std::ios::trunc);
  if (!out_) {
    throw Error(path, std::string("cannot open for writing: ") +
                          std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    RemoveTempFile(temp_path_);
  }
}

void AtomicFile::Commit() {
  out_.flush();
  if (!out_) throw Error(path_, "write failed (disk full?)");
  out_.close();
  CommitTempFile(temp_path_, path_);
  committed_ = true;
}

}  // namespace hapcine
