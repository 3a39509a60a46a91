#pragma once
// Small text helpers the readers share: ASCII lower case, a path's
// lower-case extension, and the trimming of the project's text files.

#include <string>

namespace hapcine {

// `s` with every byte through std::tolower (as unsigned char): "MP4" -> "mp4".
std::string LowerCase(std::string s);

// The path's extension with its dot, in lower case: "a/B.MP4" -> ".mp4";
// "" when there is none.
std::string LowerExtension(const std::string& path);

// `s` without spaces, tabs and carriage returns (a CRLF file's line) at
// either end.
std::string TrimBlanks(const std::string& s);

}  // namespace hapcine
