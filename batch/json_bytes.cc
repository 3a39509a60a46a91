#include "batch/json_bytes.h"

namespace hapcine::batch {
namespace {

// Length of the UTF-8 sequence starting at s[i], 0 when it is not one
// (overlong forms, surrogates and code points past U+10FFFF included).
size_t Utf8SequenceLength(const std::string& s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  size_t n = 0;
  unsigned int code = 0, min = 0;
  if ((c & 0xE0) == 0xC0) n = 2, code = c & 0x1F, min = 0x80;
  else if ((c & 0xF0) == 0xE0) n = 3, code = c & 0x0F, min = 0x800;
  else if ((c & 0xF8) == 0xF0) n = 4, code = c & 0x07, min = 0x10000;
  else return 0;
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  return code < min || surrogate || code > 0x10FFFF ? 0 : n;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

bool IsValidUtf8(const std::string& text) {
  for (size_t i = 0; i < text.size();) {
    const size_t n = Utf8SequenceLength(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

nlohmann::json JsonFromBytes(const std::string& bytes) {
  if (IsValidUtf8(bytes)) return bytes;
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (const char c : bytes) {
    hex += kHex[static_cast<unsigned char>(c) >> 4];
    hex += kHex[static_cast<unsigned char>(c) & 15];
  }
  return {{"hex", hex}};
}

std::string BytesFromJson(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  const std::string hex = value.at("hex").get<std::string>();
  std::string bytes;
  for (size_t i = 0; i + 1 < hex.size(); i += 2) {
    const int hi = HexValue(hex[i]), lo = HexValue(hex[i + 1]);
    if (hi < 0 || lo < 0 || hex.size() % 2) {
      throw nlohmann::json::type_error::create(302, "\"hex\" is not an even run of hex digits",
                                               &value);
    }
    bytes += static_cast<char>(hi * 16 + lo);
  }
  return bytes;
}

}  // namespace hapcine::batch
