#include "core/atomic_file.h"

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace hapcine {

AtomicFile::AtomicFile(const std::string& path) : temp_(path) {
  out_.open(temp_.write_path(), std::ios::out | std::ios::trunc | std::ios::binary);
  if (!out_) {
    throw Error(path, std::string("cannot open for writing: ") + std::strerror(errno));
  }
}

void AtomicFile::Commit() {
  out_.flush();
  if (!out_) throw Error(temp_.path(), "write failed (disk full?)");
  out_.close();
  if (out_.fail()) throw Error(temp_.path(), "write failed (disk full?)");
  temp_.Commit();
}

}  // namespace hapcine
