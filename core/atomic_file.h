#pragma once
// A text or binary output file written through a stream, on TempOutput
// (core/output_files.h): the data goes to a short temporary name in the
// target's folder and is renamed over the target (a symlink's final target)
// only by Commit(); an existing device or FIFO is written directly. Destroyed
// without Commit() (an exception, an early return), it removes the temporary.
// While an OutputSet is alive, Commit() only finishes the file and the set
// renames it with the command's other outputs.

#include <fstream>
#include <string>

#include "core/output_files.h"

namespace hapcine {

class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);  // throws Error if it cannot open
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Where the bytes go: the temporary, or the target when written directly.
  const std::string& temp_path() const { return temp_.write_path(); }
  // Flushes, checks for write errors, fsyncs and renames onto the final path.
  void Commit();

 private:
  TempOutput temp_;
  std::ofstream out_;  // declared after temp_: closed before the temporary is removed
};

}  // namespace hapcine
