#pragma once
// Counting the rows ahead in a stream, so a reader can reserve its rows once
// instead of growing a vector (which briefly holds twice its size).

#include <cstddef>
#include <exception>
#include <istream>
#include <vector>

namespace hapcine {

// Lines of at least `min_length` bytes (newline excluded) from the stream's
// position to its end, the position left unchanged; 0 when the stream cannot
// seek (a pipe): the caller then grows as it reads. Lines too short to be a
// row do not count, so a file of empty lines reserves nothing.
size_t CountLinesAhead(std::istream& in, size_t min_length);

// v->reserve(n), or nothing when the memory is not there: the rows then grow
// as they are read, and a file that truly needs it fails where it runs out.
template <class T>
void TryReserve(std::vector<T>* v, size_t n) {
  try {
    v->reserve(n);
  } catch (const std::exception&) {
  }
}

}  // namespace hapcine
