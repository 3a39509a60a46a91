#include "core/header_value.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hapcine {
namespace {

TEST(HeaderValueTest, EscapesWhatWouldBreakTheLine) {
  EXPECT_EQ(EscapeHeaderValue("a\nb"), "a\\nb");
  EXPECT_EQ(EscapeHeaderValue("a\rb\tc"), "a\\rb\\tc");
  EXPECT_EQ(EscapeHeaderValue("C:\\x"), "C:\\\\x");
  EXPECT_EQ(EscapeHeaderValue("k=v,w"), "k\\x3dv\\x2cw");
  EXPECT_EQ(EscapeHeaderValue(std::string("\x01\x1f\x7f", 3)), "\\x01\\x1f\\x7f");
  EXPECT_EQ(EscapeHeaderValue(" a b "), "\\x20a b\\x20");
}

TEST(HeaderValueTest, PlainTextIsUnchangedBothWays) {
  for (const std::string s : {"", "clip with spaces.mp4", "日本 crane.mkv", "é.mp4", "1920"}) {
    EXPECT_EQ(EscapeHeaderValue(s), s);
    EXPECT_EQ(UnescapeHeaderValue(s), s);
  }
}

TEST(HeaderValueTest, RoundTripsEveryByteButNul) {
  std::string all;
  for (int c = 1; c < 256; ++c) all += static_cast<char>(c);
  for (const std::string& s : {all, std::string("film\nname.mp4"), std::string("a\r\n\\n"),
                              std::string("\\"), std::string(" "), std::string("x\\"),
                              std::string("dir/tilting é\x1b[31m.mp4")}) {
    const std::string e = EscapeHeaderValue(s);
    EXPECT_EQ(e.find('\n'), std::string::npos);
    EXPECT_EQ(e.find('='), std::string::npos);
    EXPECT_EQ(e.find(','), std::string::npos);
    EXPECT_EQ(UnescapeHeaderValue(e), s);
  }
}

TEST(HeaderValueTest, BackslashesThatAreNoEscapeStayLiteral) {
  EXPECT_EQ(UnescapeHeaderValue("C:\\films\\a.mp4"), "C:\\films\\a.mp4");
  EXPECT_EQ(UnescapeHeaderValue("end\\"), "end\\");
  EXPECT_EQ(UnescapeHeaderValue("\\xZ1 \\x4"), "\\xZ1 \\x4");
  EXPECT_EQ(UnescapeHeaderValue("\\x41\\X41"), "A\\X41");
}

TEST(HeaderValueTest, WritesOneLine) {
  std::ostringstream out;
  WriteHeaderLine(out, "source", "a\nb=c");
  EXPECT_EQ(out.str(), "# source=a\\nb\\x3dc\n");
}

}  // namespace
}  // namespace hapcine
