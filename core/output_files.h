#pragma once
// How every output of hapcine reaches its final name (one helper for every
// command):
//
// - Data goes to a short, unique temporary file in the folder of the final
//   target, ".<pid>-<n>-<host>.hapcine-tmp", and is renamed over the target
//   only on commit, so a failure never leaves a half-written file and a
//   255-byte target name still works.
// - A symlink is followed (chains too) and its final target replaced; the
//   link stays. An existing device or FIFO is written directly (no temporary,
//   no rename: `-o /dev/null` works and stays a device). A directory or a
//   socket as target is an Error.
// - OutputSet declares a command's inputs and outputs up front: an output
//   that is an input, or two outputs on one path, is a UsageError before any
//   work; while the set is alive, commits only finish (flush, fsync) and the
//   renames wait for CommitAll(), so a command commits all its outputs or
//   none.
// - Live temporaries are listed in a fixed, allocation-free registry; the
//   SIGINT/SIGTERM/SIGHUP handler of InstallTempCleanupOnSignals() unlinks
//   them and dies by the signal. The first temporary made in a folder sweeps
//   that folder's temporaries left by dead processes of this host.

#include <string>
#include <vector>

namespace hapcine {

// Where the bytes of an output go.
struct OutputTarget {
  std::string path;        // as given (messages name it)
  std::string final_path;  // symlinks followed: the file a commit replaces
  bool direct = false;     // an existing device or FIFO: written in place
};
// Throws Error when `path` is (or links to) a directory or a socket.
OutputTarget ResolveOutputTarget(const std::string& path);

// The temporary file of one output. Write to write_path(), then Commit().
// Destroyed without Commit() (an exception, an early return), it removes the
// temporary; the target keeps its old content.
class TempOutput {
 public:
  TempOutput() = default;
  explicit TempOutput(const std::string& path);  // resolves; throws Error
  ~TempOutput() { Discard(); }
  TempOutput(TempOutput&& other) noexcept;
  TempOutput& operator=(TempOutput&& other) noexcept;
  TempOutput(const TempOutput&) = delete;
  TempOutput& operator=(const TempOutput&) = delete;

  const std::string& path() const { return target_.path; }
  // The temporary, or the target itself when it is written directly.
  const std::string& write_path() const {
    return target_.direct ? target_.path : temp_path_;
  }
  bool direct() const { return target_.direct; }
  // fsyncs the written file and renames it onto the final target; while an
  // OutputSet is alive only fsyncs and hands the rename to the set.
  void Commit();
  // Removes the temporary (if any); idempotent.
  void Discard() noexcept;

 private:
  friend class OutputSet;
  void Rename();  // fsync done; temporary -> final target

  OutputTarget target_;
  std::string temp_path_;  // empty when direct, committed or moved from
  int slot_ = -1;          // signal-cleanup registry slot
};

// A path a command reads or writes, and the option that named it.
struct NamedPath {
  std::string path;     // empty: not given, ignored
  std::string option;   // "INPUT", "-o", "--hjif", ...
  bool folder = false;  // an output folder (synth, batch), not a file
};

// Refuses, before any work: an output that is one of the inputs (same
// resolved path, or same device and inode) or that another output also
// names (UsageError, both named); a file output that is a directory or a
// socket, or whose folder does not exist (Error).
void CheckOutputPaths(const std::vector<NamedPath>& inputs,
                      const std::vector<NamedPath>& outputs);

// The outputs of one command, committed together. Construction checks the
// paths (CheckOutputPaths) and makes the set current: until CommitAll() or
// destruction, every TempOutput/AtomicFile commit (in any thread) only
// finishes its file. CommitAll() then renames them all (a set made inside
// another hands them to the outer one); destruction without CommitAll()
// removes them all.
class OutputSet {
 public:
  OutputSet(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  void CommitAll();
  void Adopt(TempOutput&& finished);  // called by TempOutput::Commit

 private:
  std::vector<TempOutput> finished_;
  OutputSet* previous_ = nullptr;
  bool active_ = false;
  void Deactivate() noexcept;
};

// Temporary names: ".<pid>-<n>-<8 hex of the host name>.hapcine-tmp".
// True for such a name; *pid and *this_host say whose it is.
bool ParseTempName(const std::string& name, long* pid, bool* this_host);
// Removes this host's temporaries in `dir` whose process is gone
// (kill(pid, 0) fails with ESRCH). Returns how many.
int SweepStaleTemps(const std::string& dir);
// Removes every temporary of the helper's pattern in `dir` (whoever wrote
// it: for a folder the caller holds a lock on). Returns how many.
int RemoveAllTemps(const std::string& dir);

// Installs SIGINT/SIGTERM/SIGHUP handlers that unlink the live temporaries
// and then die by the signal (default action). Call once at start-up.
void InstallTempCleanupOnSignals();
// Unlinks every live temporary; async-signal-safe (no allocation, no locks).
void RemoveLiveTempsForSignal() noexcept;

}  // namespace hapcine
