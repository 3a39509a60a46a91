#include "batch/state_files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/output_files.h"

namespace hapcine::batch {
namespace fs = std::filesystem;
namespace {

// "name.tmp-1234" (the temporary names of earlier versions) -> 1234, or -1
// if the name is not such a temp file name.
long TempPid(const std::string& name) {
  const size_t pos = name.rfind(".tmp-");
  if (pos == std::string::npos) return -1;
  const std::string digits = name.substr(pos + 5);
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  errno = 0;
  const long pid = std::strtol(digits.c_str(), nullptr, 10);  // std::stol throws when too long
  return errno == ERANGE ? -1 : pid;
}

int RemoveTempFilesIn(const fs::path& dir, bool only_dead) {
  int removed = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const long pid = TempPid(entry.path().filename().string());
    if (pid < 0) continue;
    if (only_dead && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM)) continue;
    if (fs::remove_all(entry.path(), ec) > 0) ++removed;
  }
  return removed;
}

}  // namespace

void WriteJsonAtomic(const std::string& path, const nlohmann::json& j) {
  AtomicFile out(path);
  // Paths are stored exactly (json_bytes.h); a text only shown to people (a
  // child's error message quoting a file name) gets U+FFFD for bytes that are
  // not UTF-8 rather than failing the whole batch.
  out.stream() << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  out.Commit();
}

std::optional<nlohmann::json> ReadJsonFile(const std::string& path) {
  if (!IsRegularFile(path)) return std::nullopt;
  std::ifstream in(path);
  if (!in) return std::nullopt;
  nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::nullopt;
  return j;
}

FilmLock::FilmLock(const std::string& film_dir) {
  const std::string path = (fs::path(film_dir) / kLockFile).string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(path, std::string("cannot open lock: ") + std::strerror(errno));
  locked_ = ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
}

FilmLock::~FilmLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

bool FilmIsLocked(const std::string& film_dir) {
  const std::string path = (fs::path(film_dir) / kLockFile).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  // A shared lock fails only while someone holds the exclusive one.
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return busy;
}

int CleanFilmTemp(const std::string& film_dir) {
  int removed = 0;
  std::error_code ec;
  const fs::path dir(film_dir);
  if (fs::exists(dir / kTempDir, ec)) {
    fs::remove_all(dir / kTempDir, ec);
    ++removed;
  }
  for (const fs::path& d : {dir, dir / kStepsDir}) {
    removed += RemoveTempFilesIn(d, /*only_dead=*/false);
    removed += RemoveAllTemps(d.string());
  }
  return removed;
}

int CleanDeadTempFiles(const std::string& dir) {
  return RemoveTempFilesIn(dir, true) + SweepStaleTemps(dir);
}

std::string ShardSummaryPath(const std::string& out_dir, int shard, int shards) {
  return (fs::path(out_dir) / kStateDir / "shards" /
          ("summary-" + std::to_string(shard) + "-of-" + std::to_string(shards) + ".json"))
      .string();
}

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace hapcine::batch
