#include "core/header_value.h"

namespace hapcine {
namespace {

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool NeedsHexEscape(unsigned char c) { return c < 0x20 || c == 0x7f || c == ',' || c == '='; }

}  // namespace

std::string EscapeHeaderValue(const std::string& text) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    // The reader trims blanks around a value: keep a space at either end.
    const bool edge_space = c == ' ' && (i == 0 || i + 1 == text.size());
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (NeedsHexEscape(c) || edge_space) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string UnescapeHeaderValue(const std::string& escaped) {
  std::string out;
  out.reserve(escaped.size());
  for (size_t i = 0; i < escaped.size(); ++i) {
    const char c = escaped[i];
    const char next = i + 1 < escaped.size() ? escaped[i + 1] : '\0';
    if (c != '\\') {
      out += c;
    } else if (next == '\\' || next == 'n' || next == 'r' || next == 't') {
      out += next == '\\' ? '\\' : next == 'n' ? '\n' : next == 'r' ? '\r' : '\t';
      ++i;
    } else if (next == 'x' && i + 3 < escaped.size() && HexDigit(escaped[i + 2]) >= 0 &&
               HexDigit(escaped[i + 3]) >= 0) {
      out += static_cast<char>(HexDigit(escaped[i + 2]) * 16 + HexDigit(escaped[i + 3]));
      i += 3;
    } else {
      out += c;  // not an escape: a literal backslash, as older files wrote it
    }
  }
  return out;
}

void WriteHeaderLine(std::ostream& out, const std::string& key, const std::string& value) {
  out << "# " << EscapeHeaderValue(key) << '=' << EscapeHeaderValue(value) << '\n';
}

}  // namespace hapcine
