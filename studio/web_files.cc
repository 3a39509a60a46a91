#include "studio/web_files.h"

#include <fstream>
#include <sstream>

#include "studio/http_security.h"

namespace hapcine::studio {

// Generated at build time (embed_web.cmake).
extern const EmbeddedWebFile kEmbeddedWebFiles[];
extern const size_t kEmbeddedWebFileCount;

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Served while the front end is not built in (a tree without studio/web/).
const char kPlaceholderIndex[] =
    "<!doctype html><html><head><meta charset=\"utf-8\"><title>hapcine studio</title></head>"
    "<body><h1>hapcine studio</h1><p>This build has no front end (studio/web/ was empty). "
    "The HTTP API answers at <a href=\"/api/films\">/api/films</a> (docs/studio.md).</p>"
    "</body></html>\n";

}  // namespace

std::string ContentTypeFor(const std::string& path) {
  static const std::vector<std::pair<std::string, std::string>> types = {
      {".html", "text/html; charset=utf-8"},  {".css", "text/css; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"}, {".mjs", "text/javascript; charset=utf-8"},
      {".json", "application/json"},          {".svg", "image/svg+xml"},
      {".png", "image/png"},                  {".jpg", "image/jpeg"},
      {".ico", "image/x-icon"},               {".woff2", "font/woff2"},
      {".txt", "text/plain; charset=utf-8"},  {".map", "application/json"},
  };
  for (const auto& [ext, type] : types) {
    if (EndsWith(path, ext)) return type;
  }
  return "application/octet-stream";
}

WebFiles WebFiles::Embedded() {
  WebFiles w;
  for (size_t i = 0; i < kEmbeddedWebFileCount; ++i) {
    const EmbeddedWebFile& f = kEmbeddedWebFiles[i];
    w.files_.emplace_back(f.path, std::string(reinterpret_cast<const char*>(f.data), f.size));
  }
  return w;
}

WebFiles WebFiles::Directory(const std::string& dir) {
  WebFiles w;
  w.dir_ = dir;
  return w;
}

WebFiles WebFiles::FromList(std::vector<std::pair<std::string, std::string>> files) {
  WebFiles w;
  w.files_ = std::move(files);
  return w;
}

std::optional<WebFile> WebFiles::Find(const std::string& relative) const {
  const std::optional<std::string> safe = SafeRelativePath(relative);
  if (!safe) return std::nullopt;
  if (dir_.empty()) {
    for (const auto& [path, body] : files_) {
      if (path == *safe) return WebFile{ContentTypeFor(path), body};
    }
    return std::nullopt;
  }
  const auto file = ResolveInside(dir_, *safe);
  if (!file) return std::nullopt;
  std::ifstream in(*file, std::ios::binary);
  std::ostringstream body;
  body << in.rdbuf();
  if (!in) return std::nullopt;
  return WebFile{ContentTypeFor(*safe), body.str()};
}

WebFile WebFiles::Index() const {
  if (auto index = Find("index.html")) return *index;
  return WebFile{"text/html; charset=utf-8", kPlaceholderIndex};
}

}  // namespace hapcine::studio
