#include "core/line_count.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace hapcine {
namespace {

TEST(LineCountTest, CountsLinesLongEnoughAndLeavesThePosition) {
  std::istringstream in("# a=b\nheader,row\n\n12345\n123\nlast line, no newline");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(CountLinesAhead(in, 5), 3u);  // "header,row", "12345", the last
  std::string next;
  std::getline(in, next);
  EXPECT_EQ(next, "header,row");
  EXPECT_EQ(CountLinesAhead(in, 0), 4u);  // an empty line counts at length 0
}

TEST(LineCountTest, EmptyAndExhaustedStreams) {
  std::istringstream empty("");
  EXPECT_EQ(CountLinesAhead(empty, 0), 0u);
  std::istringstream done("a\n");
  std::string line;
  std::getline(done, line);
  std::getline(done, line);  // eof
  EXPECT_EQ(CountLinesAhead(done, 0), 0u);
}

TEST(LineCountTest, TryReserveSurvivesAnImpossibleSize) {
  std::vector<double> v;
  // Past max_size() reserve throws before allocating (a size the allocator
  // itself refuses would abort under AddressSanitizer instead of throwing).
  TryReserve(&v, v.max_size() + 1);
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), 0u);
  TryReserve(&v, 10);
  EXPECT_GE(v.capacity(), 10u);
}

}  // namespace
}  // namespace hapcine
