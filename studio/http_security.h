#pragma once
// The studio's guards (docs/studio.md, "Security"): who may talk to the
// server, and which files a URL may name.
//   - Bound to a loopback address, the server answers only requests whose
//     Host is a loopback name (a web page elsewhere cannot reach it through
//     DNS rebinding) and, for changes, whose Origin (when sent) is this server.
//   - Bound to any other address, every request carries the token printed at
//     start: `?token=` once (a cookie then carries it), or
//     `Authorization: Bearer <token>`.
//   - Front-end files are named by a relative path checked word by word and
//     resolved inside the front-end folder (no "..", no symlink escape).

#include <filesystem>
#include <optional>
#include <string>

namespace hapcine::studio {

// 127.0.0.0/8, ::1, "localhost".
bool IsLoopbackHost(const std::string& host);

// The host part of a Host header ("127.0.0.1:8787" -> "127.0.0.1",
// "[::1]:80" -> "::1").
std::string HostWithoutPort(const std::string& host_header);

// 32 hex digits from the system's random source.
std::string NewToken();

// Compares in time independent of where the strings differ.
bool TokensEqual(const std::string& expected, const std::string& given);

// The token a request carries: the `token` query value, else the
// hapcine_token cookie, else an Authorization Bearer value; "" when none.
std::string RequestToken(const std::string& query_token, const std::string& cookie_header,
                         const std::string& authorization_header);

// The name of the cookie that carries the token.
constexpr const char* kTokenCookie = "hapcine_token";

// A relative front-end path ("app.js", "img/seat.svg") when every word is a
// plain name: no empty word, ".", "..", backslash, NUL, or leading "/" or ".";
// nullopt otherwise.
std::optional<std::string> SafeRelativePath(const std::string& path);

// `relative` (already SafeRelativePath) resolved inside `root`: the regular
// file it names after following symlinks, if that lies inside root's own
// canonical path; nullopt otherwise (missing, a folder, outside).
std::optional<std::filesystem::path> ResolveInside(const std::filesystem::path& root,
                                                   const std::string& relative);

}  // namespace hapcine::studio
