#include "haptics/keyframes.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "core/error.h"

namespace hapcine {
namespace {

std::vector<EffectSegment> Read(const std::string& text) {
  std::istringstream in(text);
  return ReadKeyframes(in, "fx.csv");
}

std::string ErrorOf(const std::string& text) {
  try {
    Read(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Keyframes, ReadsBothNamesCommentsAndBlankLines) {
  const auto s = Read(
      "# my film\n\nstart_s,end_s,effect,intensity\n1.0,6.0,dutch_angle,1\n"
      "  8.5 , 12 , crab_walk , -0.6\n");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].effect, CameraEffect::kDutchAngle);
  EXPECT_EQ(s[1].effect, CameraEffect::kTraveling);
  EXPECT_DOUBLE_EQ(s[1].start_s, 8.5);
  EXPECT_DOUBLE_EQ(s[1].intensity, -0.6);
}

TEST(Keyframes, RoundTrip) {
  const std::vector<EffectSegment> in = {{0.5, 2, CameraEffect::kVertigo, 0.25},
                                         {2, 3, CameraEffect::kZoomIn, -1}};
  std::ostringstream out;
  WriteKeyframes(in, out);
  const auto back = Read(out.str());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].effect, CameraEffect::kZoomIn);
  EXPECT_DOUBLE_EQ(back[0].intensity, 0.25);
}

TEST(Keyframes, RejectsBadInputWithLineNumbers) {
  const std::string h = "start_s,end_s,effect,intensity\n";
  EXPECT_NE(ErrorOf("start,end,effect\n").find("fx.csv:1:"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("empty"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,2,tilting\n").find("fx.csv:2:"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,x,tilting,1\n").find("fx.csv:2: bad end_s"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,nan,tilting,1\n").find("fx.csv:2:"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,2,dolly,1\n").find("unknown effect 'dolly'"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,2,none,1\n").find("unknown effect"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "2,1,tilting,1\n").find("after start_s"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "-1,1,tilting,1\n").find("negative"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "1,2,tilting,1.5\n").find("intensity"), std::string::npos);
  EXPECT_NE(ErrorOf(h + "# c\n1,3,tilting,1\n2,4,vertigo,1\n").find("fx.csv:4:"),
            std::string::npos);
  EXPECT_THROW(ReadKeyframesFile("/nonexistent/fx.csv"), Error);
}

// Not a regular file: refused with one line, never read (/dev/zero never
// ends; a directory used to read as an empty file).
TEST(Keyframes, RefusesWhatIsNotARegularFile) {
  const std::string dir = HAPCINE_BINARY_DIR;
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    try {
      ReadKeyframesFile(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad + (bad == dir ? ": is a directory" : ": not a regular file"));
    }
  }
}

}  // namespace
}  // namespace hapcine
