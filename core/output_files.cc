#include "core/output_files.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>

#include "core/error.h"

namespace hapcine {
namespace fs = std::filesystem;
namespace {

constexpr const char* kTempSuffix = ".hapcine-tmp";

// ---- Registry of live temporaries, read by the signal handler. Fixed
// storage, lock-free slots: the handler neither allocates nor locks.
constexpr int kMaxLiveTemps = 128;
struct LiveTemp {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
  char path[PATH_MAX];
};
LiveTemp g_live[kMaxLiveTemps];
static_assert(std::atomic<int>::is_always_lock_free, "registry slots must be lock-free");

int RegisterLiveTemp(const std::string& absolute_path) {
  if (absolute_path.size() >= PATH_MAX) return -1;  // cannot be listed; still removed normally
  for (int i = 0; i < kMaxLiveTemps; ++i) {
    int expected = 0;
    if (g_live[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_live[i].path, absolute_path.c_str(), absolute_path.size() + 1);
      g_live[i].state.store(2);
      return i;
    }
  }
  return -1;
}

void UnregisterLiveTemp(int slot) {
  if (slot >= 0) g_live[slot].state.store(0);
}

extern "C" void OnTerminatingSignal(int sig) {
  RemoveLiveTempsForSignal();
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when the handler returns: the default action
}

// ---- Temporary names.
const std::string& HostTag() {
  static const std::string tag = [] {
    char host[256] = {0};
    ::gethostname(host, sizeof(host) - 1);
    uint32_t h = 2166136261u;  // FNV-1a
    for (const char* c = host; *c; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 16777619u;
    char hex[9];
    std::snprintf(hex, sizeof(hex), "%08x", h);
    return std::string(hex);
  }();
  return tag;
}

std::string NewTempName() {
  static std::atomic<unsigned long> counter{0};
  return "." + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" + HostTag() +
         kTempSuffix;
}

// The first temporary made in a folder sweeps it (once per process).
void SweepOnce(const fs::path& dir) {
  static std::mutex mutex;
  static std::set<std::string> swept;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!swept.insert(dir.string()).second) return;
  }
  SweepStaleTemps(dir.string());
}

bool ProcessIsGone(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH; }

// Follows a chain of symlinks to the path a write through it reaches (which
// may not exist yet: a dangling link creates its target).
fs::path FollowSymlinks(const std::string& given) {
  fs::path cur = given;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(cur, ec))) return cur;
    const fs::path next = fs::read_symlink(cur, ec);
    if (ec) throw Error(given, "cannot read symbolic link: " + ec.message());
    cur = next.is_absolute() ? next : cur.parent_path() / next;
  }
  throw Error(given, "too many levels of symbolic links");
}

void FsyncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::atomic<OutputSet*> g_current_set{nullptr};

}  // namespace

// ---- Targets.

OutputTarget ResolveOutputTarget(const std::string& path) {
  if (path.empty()) throw Error("", "empty output path");
  OutputTarget t;
  t.path = path;
  t.final_path = FollowSymlinks(path).string();
  struct stat st {};
  if (::stat(t.final_path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory; give a file name");
    if (S_ISSOCK(st.st_mode)) throw Error(path, "is a socket; cannot write an output to it");
    t.direct = S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISFIFO(st.st_mode);
  }
  return t;
}

// ---- TempOutput.

TempOutput::TempOutput(const std::string& path) : target_(ResolveOutputTarget(path)) {
  if (target_.direct) return;
  const fs::path final_path(target_.final_path);
  const fs::path dir = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
  SweepOnce(dir);
  const std::string temp = (dir / NewTempName()).string();
  std::error_code ec;
  slot_ = RegisterLiveTemp(fs::absolute(temp, ec).string());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const std::string reason = std::string("cannot open for writing: ") + std::strerror(errno);
    UnregisterLiveTemp(slot_);
    slot_ = -1;
    throw Error(path, reason);
  }
  ::close(fd);
  temp_path_ = temp;
}

TempOutput::TempOutput(TempOutput&& other) noexcept
    : target_(std::move(other.target_)),
      temp_path_(std::move(other.temp_path_)),
      slot_(other.slot_) {
  other.temp_path_.clear();
  other.slot_ = -1;
}

TempOutput& TempOutput::operator=(TempOutput&& other) noexcept {
  if (this != &other) {
    Discard();
    target_ = std::move(other.target_);
    temp_path_ = std::move(other.temp_path_);
    slot_ = other.slot_;
    other.temp_path_.clear();
    other.slot_ = -1;
  }
  return *this;
}

void TempOutput::Commit() {
  if (target_.direct || temp_path_.empty()) return;  // written in place / already done
  FsyncPath(temp_path_, O_RDONLY);  // data on disk before a name points at it
  if (OutputSet* set = g_current_set.load()) {
    set->Adopt(std::move(*this));
    return;
  }
  Rename();
}

void TempOutput::Rename() {
  // Keep the mode of the file being replaced (e.g. a symlink's target).
  struct stat st {};
  if (::stat(target_.final_path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
    ::chmod(temp_path_.c_str(), st.st_mode & 07777);
  }
  if (std::rename(temp_path_.c_str(), target_.final_path.c_str()) != 0) {
    const std::string reason = std::string("cannot rename temporary file: ") + std::strerror(errno);
    Discard();
    throw Error(target_.path, reason);
  }
  UnregisterLiveTemp(slot_);
  slot_ = -1;
  temp_path_.clear();
  const fs::path dir = fs::path(target_.final_path).parent_path();
  FsyncPath(dir.empty() ? "." : dir.string(), O_RDONLY | O_DIRECTORY);  // the new name too
}

void TempOutput::Discard() noexcept {
  if (temp_path_.empty()) return;
  ::unlink(temp_path_.c_str());
  UnregisterLiveTemp(slot_);
  slot_ = -1;
  temp_path_.clear();
}

// ---- Checking a command's paths.

namespace {

struct Identity {
  fs::path canonical;
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  bool device = false;  // a char/block device: many writers are harmless
};

Identity IdentityOf(const std::string& path) {
  Identity id;
  fs::path followed = path;
  try {
    followed = FollowSymlinks(path);  // a dangling link names the file it would create
  } catch (const Error&) {
  }
  std::error_code ec;
  id.canonical = fs::weakly_canonical(followed, ec);
  if (ec) id.canonical = fs::absolute(followed, ec).lexically_normal();
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
    id.device = S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode);
  }
  return id;
}

bool SameFile(const Identity& a, const Identity& b) {
  return a.canonical == b.canonical || (a.exists && b.exists && a.dev == b.dev && a.ino == b.ino);
}

std::string Named(const NamedPath& p) {
  return (p.option.empty() || p.option == p.path ? "" : p.option + " ") + p.path;
}

void CheckOutputPlace(const NamedPath& out) {
  std::error_code ec;
  if (out.folder) {
    if (fs::exists(out.path, ec) && !fs::is_directory(out.path, ec))
      throw Error(out.path, "is not a folder");
    return;
  }
  const OutputTarget t = ResolveOutputTarget(out.path);  // directory, socket: Error
  if (t.direct) return;
  const fs::path parent = fs::path(t.final_path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error(out.path, "output folder does not exist");
}

}  // namespace

void CheckOutputPaths(const std::vector<NamedPath>& inputs,
                      const std::vector<NamedPath>& outputs) {
  std::vector<std::pair<const NamedPath*, Identity>> ins, outs;
  for (const NamedPath& in : inputs) {
    if (!in.path.empty()) ins.emplace_back(&in, IdentityOf(in.path));
  }
  for (const NamedPath& out : outputs) {
    if (out.path.empty()) continue;
    const Identity id = IdentityOf(out.path);
    if (!id.device) {
      for (const auto& [in, in_id] : ins) {
        if (SameFile(id, in_id))
          throw UsageError(Named(out) + ": is also the input " + Named(*in) +
                           " (it would be overwritten); choose another output");
      }
      for (const auto& [other, other_id] : outs) {
        if (SameFile(id, other_id))
          throw UsageError(Named(*other) + " and " + Named(out) +
                           " are the same file; give each output its own path");
      }
    }
    outs.emplace_back(&out, id);
  }
  for (const auto& entry : outs) CheckOutputPlace(*entry.first);
}

// ---- OutputSet.

namespace {
std::mutex g_adopt_mutex;
}

OutputSet::OutputSet(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  CheckOutputPaths(inputs, outputs);
  previous_ = g_current_set.exchange(this);
  active_ = true;
}

OutputSet::~OutputSet() {
  Deactivate();
  std::lock_guard<std::mutex> lock(g_adopt_mutex);
  finished_.clear();  // each removes its temporary
}

void OutputSet::Deactivate() noexcept {
  if (!active_) return;
  g_current_set.store(previous_);
  active_ = false;
}

void OutputSet::Adopt(TempOutput&& finished) {
  std::lock_guard<std::mutex> lock(g_adopt_mutex);
  finished_.push_back(std::move(finished));
}

void OutputSet::CommitAll() {
  Deactivate();
  std::vector<TempOutput> all;
  {
    std::lock_guard<std::mutex> lock(g_adopt_mutex);
    all.swap(finished_);
  }
  if (previous_) {  // nested: the outer set commits them with its own
    for (TempOutput& t : all) previous_->Adopt(std::move(t));
    return;
  }
  for (TempOutput& t : all) t.Rename();  // a failure throws; `all` removes the rest
}

// ---- Temporary names and sweeping.

bool ParseTempName(const std::string& name, long* pid, bool* this_host) {
  const std::string suffix = kTempSuffix;
  if (name.size() < 1 + suffix.size() || name[0] != '.' ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string body = name.substr(1, name.size() - 1 - suffix.size());  // pid-n-host
  const size_t a = body.find('-');
  const size_t b = a == std::string::npos ? a : body.find('-', a + 1);
  if (b == std::string::npos) return false;
  const std::string p = body.substr(0, a), n = body.substr(a + 1, b - a - 1),
                    host = body.substr(b + 1);
  auto digits = [](const std::string& s) {
    return !s.empty() && s.size() < 12 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!digits(p) || !digits(n) || host.size() != 8 ||
      host.find_first_not_of("0123456789abcdef") != std::string::npos)
    return false;
  if (pid) *pid = std::stol(p);
  if (this_host) *this_host = host == HostTag();
  return true;
}

namespace {
int RemoveTempsIn(const std::string& dir, bool only_dead) {
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    long pid = 0;
    bool here = false;
    if (!ParseTempName(it->path().filename().string(), &pid, &here)) continue;
    if (here && pid == ::getpid()) continue;  // ours, live (or removed by its owner)
    if (only_dead && !(here && ProcessIsGone(pid))) continue;
    if (::unlink(it->path().c_str()) == 0) ++removed;
  }
  return removed;
}
}  // namespace

int SweepStaleTemps(const std::string& dir) { return RemoveTempsIn(dir, /*only_dead=*/true); }
int RemoveAllTemps(const std::string& dir) { return RemoveTempsIn(dir, /*only_dead=*/false); }

// ---- Signals.

void RemoveLiveTempsForSignal() noexcept {
  for (LiveTemp& t : g_live) {
    if (t.state.load() == 2) ::unlink(t.path);
  }
}

void InstallTempCleanupOnSignals() {
  struct sigaction sa {};
  sa.sa_handler = OnTerminatingSignal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // nohup and friends: stay ignored
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace hapcine
