#include "core/line_count.h"

namespace hapcine {

size_t CountLinesAhead(std::istream& in, size_t min_length) {
  const std::istream::pos_type start = in.tellg();
  if (start == std::istream::pos_type(-1)) {
    in.clear();
    return 0;
  }
  size_t lines = 0;
  size_t length = 0;  // of the line being read
  char buf[1 << 16];
  while (in.read(buf, sizeof buf), in.gcount() > 0) {
    for (const char* p = buf; p != buf + in.gcount(); ++p) {
      if (*p != '\n') {
        ++length;
        continue;
      }
      lines += length >= min_length;
      length = 0;
    }
  }
  lines += length >= min_length && length > 0;
  in.clear();
  in.seekg(start);
  return lines;
}

}  // namespace hapcine
