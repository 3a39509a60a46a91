#include "core/optional_name.h"

#include <gtest/gtest.h>

#include <optional>
#include <sstream>
#include <string>

namespace hapcine {
namespace {

TEST(OptionalNameTest, ReadsLikeAnOptionalString) {
  OptionalName n;
  EXPECT_FALSE(n.has_value());
  EXPECT_FALSE(n);
  EXPECT_EQ(n.value_or("none"), "none");
  EXPECT_THROW(n.value(), std::bad_optional_access);
  n = "rotation+zoom";
  ASSERT_TRUE(n);
  EXPECT_EQ(*n, "rotation+zoom");
  EXPECT_EQ(n->size(), 13u);
  EXPECT_EQ(n, "rotation+zoom");
  EXPECT_NE(n, "rotation");
  EXPECT_EQ(n, std::string("rotation+zoom"));
  EXPECT_EQ(n, OptionalName(std::string("rotation+zoom")));
  n = std::nullopt;
  EXPECT_FALSE(n);
  EXPECT_NE(n, "");
  n = "";
  EXPECT_TRUE(n.has_value());
  EXPECT_EQ(*n, "");
  n.reset();
  EXPECT_EQ(std::optional<std::string>(n), std::nullopt);
  std::ostringstream out;
  out << OptionalName("tilting") << " " << OptionalName();
  EXPECT_EQ(out.str(), "tilting (none)");
}

TEST(OptionalNameTest, IsSmallAndEqualTextsShareOneEntry) {
  EXPECT_LE(sizeof(OptionalName), 2u);
  const std::string text = "a text with\nodd bytes \x01 é";
  EXPECT_EQ(OptionalName(text), OptionalName(text.c_str()));
  EXPECT_EQ(&*OptionalName(text), &*OptionalName(text));
}

TEST(OptionalNameTest, RecentNameRepeatsAndSwitches) {
  RecentName recent;
  OptionalName a, b, c;
  ASSERT_TRUE(recent.Make("general", &a));
  ASSERT_TRUE(recent.Make("general", &b));
  ASSERT_TRUE(recent.Make("static", &c));
  EXPECT_EQ(a, b);
  EXPECT_EQ(*c, "static");
}

}  // namespace
}  // namespace hapcine
