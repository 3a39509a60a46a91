#include "core/text.h"

#include <gtest/gtest.h>

namespace hapcine {
namespace {

TEST(LowerCaseTest, LowersAsciiAndKeepsOtherBytes) {
  EXPECT_EQ(LowerCase("MP4 Path_1"), "mp4 path_1");
  EXPECT_EQ(LowerCase(""), "");
  // Bytes above 127 (UTF-8) pass through: no sign-extension trouble.
  EXPECT_EQ(LowerCase("\xC3\x89T\xC3\x89"), "\xC3\x89t\xC3\x89");
}

TEST(LowerExtensionTest, TakesTheLastExtensionWithItsDot) {
  EXPECT_EQ(LowerExtension("films/Clip.MP4"), ".mp4");
  EXPECT_EQ(LowerExtension("plate.1001.EXR"), ".exr");
  EXPECT_EQ(LowerExtension("dir.d/noext"), "");
  EXPECT_EQ(LowerExtension(".hidden"), "");  // a dot file's name is its stem
  EXPECT_EQ(LowerExtension(""), "");
}

TEST(TrimBlanksTest, TrimsSpacesTabsAndCarriageReturnsOnly) {
  EXPECT_EQ(TrimBlanks(" \t1.5\r"), "1.5");
  EXPECT_EQ(TrimBlanks("a b"), "a b");
  EXPECT_EQ(TrimBlanks(" \t\r"), "");
  EXPECT_EQ(TrimBlanks(""), "");
  EXPECT_EQ(TrimBlanks("\nx\n"), "\nx\n");  // line breaks are the reader's business
}

}  // namespace
}  // namespace hapcine
