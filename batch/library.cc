#include "batch/library.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>

#include "batch/content_hash.h"
#include "batch/json_bytes.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/text.h"

namespace hapcine::batch {
namespace fs = std::filesystem;
namespace {

std::string Trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string Absolute(const fs::path& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) abs = p;
  return abs.lexically_normal().string();
}

std::vector<std::string> ReadManifest(const fs::path& manifest) {
  InputFile file(manifest.string());
  std::ifstream& in = file.stream();
  const fs::path base = manifest.parent_path();
  const bool csv = LowerCase(manifest.extension().string()) == ".csv";
  std::vector<std::string> paths;
  std::string line;
  int line_no = 0;
  int path_column = -1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find('\0') != std::string::npos) {
      throw Error(manifest.string() + ":" + std::to_string(line_no),
                  "not a text manifest (binary data); give a folder, a video or a list of paths");
    }
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line = line.substr(3);  // BOM
    if (csv) {
      if (Trim(line).empty()) continue;
      std::vector<std::string> fields = SplitCsvLine(line);
      if (path_column < 0) {
        for (size_t i = 0; i < fields.size(); ++i) {
          if (LowerCase(Trim(fields[i])) == "path") path_column = static_cast<int>(i);
        }
        if (path_column < 0) {
          throw Error(manifest.string() + ":" + std::to_string(line_no),
                      "CSV manifest needs a header row with a 'path' column");
        }
        continue;
      }
      if (static_cast<size_t>(path_column) >= fields.size()) {
        throw Error(manifest.string() + ":" + std::to_string(line_no), "row has no 'path' field");
      }
      line = fields[path_column];
    }
    const std::string entry = Trim(line);
    if (entry.empty() || (!csv && entry[0] == '#')) continue;
    fs::path p(entry);
    if (p.is_relative()) p = base / p;
    paths.push_back(Absolute(p));
  }
  return paths;
}

std::vector<std::string> ScanFolder(const fs::path& folder) {
  std::vector<std::string> paths;
  std::error_code ec;
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
  if (ec) throw Error(folder.string(), "cannot list folder: " + ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) throw Error(folder.string(), "cannot list folder: " + ec.message());
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    if (!name.empty() && name[0] == '.') {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;  // follows symlinks
    std::string ext = p.extension().string();
    if (!ext.empty()) ext = ext.substr(1);
    if (IsVideoExtension(ext)) paths.push_back(Absolute(p));
  }
  return paths;
}

}  // namespace

bool IsVideoExtension(const std::string& extension) {
  static const std::set<std::string> kVideo = {"mp4", "m4v",  "mov", "mkv", "webm", "avi",
                                               "mpg", "mpeg", "m2v", "ts",  "m2ts", "mts",
                                               "wmv", "flv",  "3gp", "ogv", "vob",  "mxf"};
  return kVideo.count(LowerCase(extension)) > 0;
}

std::vector<std::string> ListLibrary(const std::string& library) {
  std::error_code ec;
  const fs::path root(library);
  if (!fs::exists(root, ec)) throw Error(library, "no such file or folder");
  // A single video is a library of one (its manifest would be binary data).
  if (fs::is_regular_file(root, ec) && IsVideoExtension(root.extension().string().substr(
                                         root.extension().empty() ? 0 : 1))) {
    return {Absolute(root)};
  }
  std::vector<std::string> paths =
      fs::is_directory(root, ec) ? ScanFolder(root) : ReadManifest(root);
  std::sort(paths.begin(), paths.end());
  paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
  return paths;
}

std::string FileStem(const std::string& path) { return fs::path(path).stem().string(); }

namespace {
// Cuts `s` to at most `bytes` bytes without splitting a UTF-8 character.
void CutUtf8(std::string& s, size_t bytes) {
  if (s.size() <= bytes) return;
  size_t cut = bytes;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  s.resize(cut);
}
}  // namespace

std::string OutputStem(const std::string& file_stem, const std::vector<std::string>& models) {
  constexpr size_t kNameMax = 255;
  size_t longest_suffix = std::string(".camera.csv").size();
  for (const std::string& m : models) {
    longest_suffix = std::max(longest_suffix, ("." + m + ".haptic.csv").size());
  }
  std::string stem = file_stem;
  CutUtf8(stem, kNameMax > longest_suffix + 1 ? kNameMax - longest_suffix : 1);
  return stem.empty() ? "film" : stem;
}

std::string FilmId(const std::string& absolute_path) {
  std::string stem = FileStem(absolute_path);
  std::string safe;
  for (char c : stem) {
    const auto u = static_cast<unsigned char>(c);
    safe += (u < 0x20 || u == 0x7f || c == '/') ? '_' : c;
  }
  // The id names a folder and appears in JSON and logs: a name that is not
  // UTF-8 keeps its ASCII only (the hash below still tells films apart).
  if (!IsValidUtf8(safe)) {
    for (char& c : safe) c = static_cast<unsigned char>(c) >= 0x80 ? '_' : c;
  }
  if (safe.empty()) safe = "film";
  if (safe[0] == '.') safe[0] = '_';
  if (safe.size() > 80) {
    size_t cut = 80;
    // Back up to a UTF-8 lead byte so a multi-byte character is never split.
    while (cut > 0 && (static_cast<unsigned char>(safe[cut]) & 0xC0) == 0x80) --cut;
    safe.resize(cut);
  }
  return safe + "-" + Fnv1a64Hex(absolute_path).substr(0, 8);
}

std::vector<std::string> SplitArgs(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) {
        quote = 0;
      } else if (c == '\\' && quote == '"' && i + 1 < text.size()) {
        word += text[++i];
      } else {
        word += c;
      }
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == '\\' && i + 1 < text.size()) {
      word += text[++i];
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (quote) throw UsageError("unterminated quote in arguments: " + text);
  if (in_word) words.push_back(word);
  return words;
}

}  // namespace hapcine::batch
