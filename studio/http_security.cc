#include "studio/http_security.h"

#include <random>
#include <sstream>

namespace hapcine::studio {

bool IsLoopbackHost(const std::string& host) {
  if (host == "localhost" || host == "::1" || host == "[::1]") return true;
  // 127.0.0.0/8, written as a dotted quad.
  if (host.rfind("127.", 0) != 0) return false;
  int dots = 0;
  for (char c : host) {
    if (c == '.') {
      ++dots;
    } else if (c < '0' || c > '9') {
      return false;
    }
  }
  return dots == 3;
}

std::string HostWithoutPort(const std::string& host_header) {
  if (!host_header.empty() && host_header[0] == '[') {
    const size_t close = host_header.find(']');
    return close == std::string::npos ? host_header : host_header.substr(1, close - 1);
  }
  // More than one ':' is a bare IPv6 address, not host:port.
  const size_t colon = host_header.find(':');
  if (colon == std::string::npos || host_header.find(':', colon + 1) != std::string::npos)
    return host_header;
  return host_header.substr(0, colon);
}

std::string NewToken() {
  std::random_device random;  // /dev/urandom on Linux
  std::ostringstream s;
  s << std::hex;
  for (int i = 0; i < 4; ++i) {
    const uint32_t word = random();
    for (int k = 7; k >= 0; --k) s << ((word >> (4 * k)) & 0xf);
  }
  return s.str();
}

bool TokensEqual(const std::string& expected, const std::string& given) {
  if (expected.empty() || expected.size() != given.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    diff |= static_cast<unsigned char>(expected[i] ^ given[i]);
  return diff == 0;
}

namespace {

// The value of cookie `name` in a Cookie header ("a=1; hapcine_token=x").
std::string CookieValue(const std::string& header, const std::string& name) {
  size_t pos = 0;
  while (pos < header.size()) {
    size_t end = header.find(';', pos);
    if (end == std::string::npos) end = header.size();
    std::string pair = header.substr(pos, end - pos);
    const size_t start = pair.find_first_not_of(' ');
    pair = start == std::string::npos ? "" : pair.substr(start);
    if (pair.rfind(name + "=", 0) == 0) return pair.substr(name.size() + 1);
    pos = end + 1;
  }
  return "";
}

}  // namespace

std::string RequestToken(const std::string& query_token, const std::string& cookie_header,
                         const std::string& authorization_header) {
  if (!query_token.empty()) return query_token;
  const std::string cookie = CookieValue(cookie_header, kTokenCookie);
  if (!cookie.empty()) return cookie;
  const std::string bearer = "Bearer ";
  if (authorization_header.rfind(bearer, 0) == 0) return authorization_header.substr(bearer.size());
  return "";
}

std::optional<std::string> SafeRelativePath(const std::string& path) {
  if (path.empty() || path.size() > 512) return std::nullopt;
  size_t pos = 0;
  while (pos <= path.size()) {
    size_t end = path.find('/', pos);
    if (end == std::string::npos) end = path.size();
    const std::string word = path.substr(pos, end - pos);
    // No empty word ("a//b", leading '/'), no dot file, "." or "..".
    if (word.empty() || word[0] == '.') return std::nullopt;
    for (char c : word) {
      if (c == '\\' || c == '\0' || static_cast<unsigned char>(c) < 0x20) return std::nullopt;
    }
    pos = end + 1;
  }
  return path;
}

std::optional<std::filesystem::path> ResolveInside(const std::filesystem::path& root,
                                                   const std::string& relative) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path target = fs::canonical(base / relative, ec);
  if (ec || !fs::is_regular_file(target, ec)) return std::nullopt;
  // Inside: base's words are a prefix of target's.
  auto t = target.begin();
  for (auto b = base.begin(); b != base.end(); ++b, ++t) {
    if (t == target.end() || *t != *b) return std::nullopt;
  }
  return target;
}

}  // namespace hapcine::studio
