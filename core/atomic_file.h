#pragma once
// Write-then-rename output files. Nothing half-written ever sits under the
// final name: the data goes to "<path>.tmp-<pid>" and is renamed over the
// target only by Commit(). If the writer is destroyed without Commit() (an
// exception, an early return) the temporary file is removed.

#include <fstream>
#include <string>

namespace hapcine {

class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);  // throws Error if it cannot open
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  const std::string& temp_path() const { return temp_path_; }
  // Flushes, checks for write errors, fsyncs and renames onto the final path.
  void Commit();

 private:
  std::string path_;
  std::string temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

// Temporary name for an output written by another library (e.g. an encoder
// that opens the file itself). Pair with CommitTempFile / RemoveTempFile.
std::string TempPathFor(const std::string& final_path);
void CommitTempFile(const std::string& temp_path, const std::string& final_path);
void RemoveTempFile(const std::string& temp_path) noexcept;

}  // namespace hapcine
