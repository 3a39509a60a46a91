#pragma once
// The session journal (`<participant>.journal.jsonl`): one JSON object per
// line, appended and fsync'ed as each trial is answered, so that a crash, a
// power cut or Ctrl-C loses at most the trial being shown. The first line
// names the plan and the participant; a restart reads the journal back and
// resumes at the first unanswered trial. A last line cut short by a crash (no
// newline, or not parseable) is dropped and truncated away; any other bad
// line is an error, never silently skipped.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace hapcine::study {

class Journal {
 public:
  // Opens (creating if needed) the journal at `path` for this plan and
  // participant. Throws Error(path, ...) if it belongs to another plan or
  // participant, or is corrupt before its last line.
  Journal(const std::string& path, const std::string& plan_id, const std::string& participant);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Records read back at open (header excluded), in file order.
  const std::vector<nlohmann::json>& records() const { return records_; }
  // Appends one record as a line and fsyncs before returning.
  void Append(const nlohmann::json& record);
  const std::string& path() const { return path_; }

 private:
  // Reads the records after the header into records_; returns the bytes of
  // `content` that are valid (a torn last line is not).
  size_t ParseRecords(const std::string& content, const std::vector<std::string>& lines,
                      const std::string& plan_id, const std::string& participant);
  void WriteLine(const std::string& line);
  std::string path_;
  int fd_ = -1;
  std::vector<nlohmann::json> records_;
};

}  // namespace hapcine::study
