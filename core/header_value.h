#pragma once
// Escaping of the "# key=value" header lines of the project's CSV files
// (camera path, haptic track). A value is free text (a file name may hold a
// newline, a comma or '='), but a header line must stay one line with one
// '=' and no surrounding blanks, so the writer escapes and the reader undoes it:
//   \\  backslash        \n  line feed        \r  carriage return
//   \t  tab              \xHH  any other byte below 0x20, 0x7f, ',' and '=',
//                        and a space at either end of the text (\x20)
// Every other byte, UTF-8 included, is written as it is. A backslash not
// followed by one of these escapes is kept literally on reading, so a header
// without backslashes, or with a Windows path such as C:\films\a.mp4, reads
// as it always did. The formats are documented in docs/formats.md.

#include <ostream>
#include <string>

namespace hapcine {

std::string EscapeHeaderValue(const std::string& text);
std::string UnescapeHeaderValue(const std::string& escaped);

// Writes "# key=value\n" with both key and value escaped.
void WriteHeaderLine(std::ostream& out, const std::string& key, const std::string& value);

}  // namespace hapcine
