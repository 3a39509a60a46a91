#include "batch/json_bytes.h"

#include <gtest/gtest.h>

namespace hapcine::batch {
namespace {

TEST(JsonBytesTest, Utf8TextStaysAPlainString) {
  for (const std::string text : {"", "films/a.mp4", "films/é clip 日本.mkv", "\xF0\x9F\x8E\xAC.mp4"}) {
    EXPECT_TRUE(IsValidUtf8(text)) << text;
    const nlohmann::json j = JsonFromBytes(text);
    ASSERT_TRUE(j.is_string()) << text;
    EXPECT_EQ(BytesFromJson(nlohmann::json::parse(j.dump())), text);
  }
}

TEST(JsonBytesTest, OtherBytesRoundTripThroughHex) {
  // A stray byte, a cut sequence, an overlong '/', a surrogate, past U+10FFFF.
  for (const std::string& text : {std::string("a\xff.mp4"), std::string("\xC3"),
                                 std::string("\xC0\xAF"), std::string("\xED\xA0\x80"),
                                 std::string("\xF4\x90\x80\x80"), std::string("x\0y", 3)}) {
    const bool valid = IsValidUtf8(text);
    EXPECT_EQ(valid, text == std::string("x\0y", 3));
    const nlohmann::json j = JsonFromBytes(text);
    EXPECT_EQ(j.is_string(), valid);
    EXPECT_EQ(BytesFromJson(nlohmann::json::parse(j.dump())), text);
  }
}

TEST(JsonBytesTest, MalformedHexIsAnError) {
  EXPECT_THROW(BytesFromJson(nlohmann::json{{"hex", "abc"}}), nlohmann::json::exception);
  EXPECT_THROW(BytesFromJson(nlohmann::json{{"hex", "zz"}}), nlohmann::json::exception);
  EXPECT_THROW(BytesFromJson(nlohmann::json(42)), nlohmann::json::exception);
}

}  // namespace
}  // namespace hapcine::batch
