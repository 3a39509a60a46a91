#include "study/journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "study/json_util.h"

namespace hapcine::study {
using nlohmann::json;

namespace {
const char* const kFormat = "hapcine-study-journal";

void FsyncDirectoryOf(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dfd = open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    fsync(dfd);
    close(dfd);
  }
}

// The journal's bytes, or "" with *existed false when there is none yet. One
// that exists must be a regular file (a FIFO would block, a device never end).
std::string ReadExisting(const std::string& path, bool* existed) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) CheckRegularFile(path);
  std::ifstream in(path, std::ios::binary);
  *existed = static_cast<bool>(in);
  if (!in) return "";
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The complete lines; a trailing fragment without '\n' is a write cut short
// by a crash and is left out.
std::vector<std::string> CompleteLines(const std::string& content) {
  std::vector<std::string> lines;
  for (size_t pos = 0; pos < content.size();) {
    const size_t nl = content.find('\n', pos);
    if (nl == std::string::npos) break;
    lines.push_back(content.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return lines;
}

// The header line must name this plan and participant.
void CheckHeader(const json& j, const std::string& path, const std::string& plan_id,
                 const std::string& participant) {
  if (!j.is_object() || j.value("format", "") != kFormat)
    throw Error(path, "not a hapcine study journal");
  const std::string jp = StringField(j, "plan_id", path, "line 1");
  const std::string jpart = StringField(j, "participant", path, "line 1");
  if (jp != plan_id) throw Error(path, "journal belongs to plan " + jp + ", not " + plan_id);
  if (jpart != participant)
    throw Error(path, "journal belongs to participant " + jpart + ", not " + participant);
}

}  // namespace

size_t Journal::ParseRecords(const std::string& content, const std::vector<std::string>& lines,
                             const std::string& plan_id, const std::string& participant) {
  size_t offset = 0;  // bytes of valid content so far
  for (size_t i = 0; i < lines.size(); ++i) {
    json j;
    try {
      j = json::parse(lines[i]);
    } catch (const json::exception&) {
      // A last line that does not parse is a torn write: dropped, not fatal.
      if (i + 1 == lines.size() && offset + lines[i].size() + 1 == content.size()) break;
      throw Error(path_ + ":" + std::to_string(i + 1), "corrupt journal line (not JSON)");
    }
    if (i == 0) {
      CheckHeader(j, path_, plan_id, participant);
    } else {
      if (!j.is_object())
        throw Error(path_ + ":" + std::to_string(i + 1), "journal record is not an object");
      records_.push_back(std::move(j));
    }
    offset += lines[i].size() + 1;
  }
  return offset;
}

Journal::Journal(const std::string& path, const std::string& plan_id,
                 const std::string& participant)
    : path_(path) {
  bool existed = false;
  const std::string content = ReadExisting(path, &existed);
  const std::vector<std::string> lines = CompleteLines(content);
  const size_t keep = ParseRecords(content, lines, plan_id, participant);
  fd_ = open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(path, std::string("cannot open journal: ") + std::strerror(errno));
  if (keep < content.size()) {
    // Drop the torn tail so the next record starts on a fresh line.
    if (ftruncate(fd_, static_cast<off_t>(keep)) != 0 || fsync(fd_) != 0)
      throw Error(path, std::string("cannot truncate torn journal tail: ") + std::strerror(errno));
  }
  if (lseek(fd_, 0, SEEK_END) < 0) throw Error(path, std::string("seek: ") + std::strerror(errno));
  if (keep == 0) {
    if (content.size() > 0 && existed && lines.size() > 0)
      throw Error(path, "journal header is corrupt");
    WriteLine(json{{"format", kFormat},
                   {"version", 1},
                   {"plan_id", plan_id},
                   {"participant", participant},
                   {"created_utc", UtcNow()}}
                  .dump());
    FsyncDirectoryOf(path);
  }
}

Journal::~Journal() {
  if (fd_ >= 0) close(fd_);
}

void Journal::WriteLine(const std::string& line) {
  const std::string data = line + "\n";
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = write(fd_, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(path_, std::string("journal write failed: ") + std::strerror(errno));
    }
    done += static_cast<size_t>(n);
  }
  if (fsync(fd_) != 0)
    throw Error(path_, std::string("journal fsync failed: ") + std::strerror(errno));
}

void Journal::Append(const json& record) {
  WriteLine(record.dump());
  records_.push_back(record);
}

}  // namespace hapcine::study
