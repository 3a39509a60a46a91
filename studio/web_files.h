#pragma once
// The front end's files (studio/web/ in the source tree): embedded in the
// binary at build time (studio/embed_web.cmake), so `hapcine studio` needs no
// installed data; or, for front-end work, read from a folder on each request
// (`hapcine studio --web-dir studio/web`). Either way only files named by a
// safe relative path (http_security.h) are served.

#include <optional>
#include <string>
#include <vector>

namespace hapcine::studio {

struct WebFile {
  std::string content_type;
  std::string body;
};

// One file of the embedded set (generated source).
struct EmbeddedWebFile {
  const char* path;  // relative to studio/web/
  const unsigned char* data;
  size_t size;
};

class WebFiles {
 public:
  // The files built into this binary.
  static WebFiles Embedded();
  // The files of `dir`, read when asked for.
  static WebFiles Directory(const std::string& dir);
  // Built from an explicit list (tests).
  static WebFiles FromList(std::vector<std::pair<std::string, std::string>> files);

  // The file at `relative` ("index.html", "js/app.js"); nullopt for a path
  // that is not safe, not in the set, or escapes the folder.
  std::optional<WebFile> Find(const std::string& relative) const;
  // index.html, or a page saying the front end is missing.
  WebFile Index() const;

 private:
  std::string dir_;  // empty: files_ below
  std::vector<std::pair<std::string, std::string>> files_;
};

// By extension: "text/html; charset=utf-8", "text/javascript; charset=utf-8", ...
std::string ContentTypeFor(const std::string& path);

}  // namespace hapcine::studio
