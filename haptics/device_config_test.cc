#include "haptics/device_config.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(DeviceConfig, ParsesRolesMountsAndLimits) {
  const SeatConfig c = ParseSeatConfig(R"({"devices": [
      {"role": "head", "serial": "FTB1", "mount": "behind", "max_force_n": 5},
      {"role": "left", "serial": "FTA1"},
      {"role": "right", "serial": "FTA2", "seat_from_falcon": [[0,-1,0],[1,0,0],[0,0,1]]}]})",
                                       "seat.json");
  ASSERT_TRUE(c.roles[0] && c.roles[1] && c.roles[2]);
  EXPECT_EQ(c.roles[0]->serial, "FTB1");
  EXPECT_EQ(c.roles[0]->seat_from_falcon(0, 0), -1);
  EXPECT_EQ(c.roles[0]->seat_from_falcon(2, 2), -1);
  EXPECT_DOUBLE_EQ(*c.roles[0]->max_force_n, 5);
  EXPECT_TRUE(c.roles[1]->seat_from_falcon.isIdentity());
  EXPECT_FALSE(c.roles[1]->max_force_n);
  EXPECT_EQ(c.roles[2]->seat_from_falcon(0, 1), -1);
}

TEST(DeviceConfig, MissingRolesAreAbsent) {
  const SeatConfig c = ParseSeatConfig(R"({"devices": [{"role": "right", "serial": "X"}]})", "s");
  EXPECT_FALSE(c.roles[0]);
  EXPECT_FALSE(c.roles[1]);
  EXPECT_TRUE(c.roles[2]);
}

TEST(DeviceConfig, BadInputIsAOneLineErrorNamingTheFile) {
  const char* bad[] = {
      "not json",
      R"({"devices": 3})",
      R"({"devices": [{"serial": "X"}]})",
      R"({"devices": [{"role": "foot", "serial": "X"}]})",
      R"({"devices": [{"role": "head"}]})",
      R"({"devices": [{"role": "head", "serial": ""}]})",
      R"({"devices": [{"role": "head", "serial": "A"}, {"role": "head", "serial": "B"}]})",
      R"({"devices": [{"role": "head", "serial": "A"}, {"role": "left", "serial": "A"}]})",
      R"({"devices": [{"role": "head", "serial": "A", "mount": "sideways"}]})",
      R"({"devices": [{"role": "head", "serial": "A", "max_force_n": 20}]})",
      R"({"devices": [{"role": "head", "serial": "A", "max_force_n": -1}]})",
      R"({"devices": [{"role": "head", "serial": "A", "seat_from_falcon": [[2,0,0],[0,1,0],[0,0,1]]}]})",
      R"({"devices": [{"role": "head", "serial": "A", "seat_from_falcon": [[-1,0,0],[0,1,0],[0,0,1]]}]})",
      R"({"devices": [{"role": "head", "serial": "A", "seat_from_falcon": [[1,0],[0,1]]}]})",
  };
  for (const char* text : bad) {
    try {
      ParseSeatConfig(text, "seat.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "seat.json") << text;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  EXPECT_THROW(ReadSeatConfigFile("/nonexistent/seat.json"), Error);
}

// Not a regular file: refused with one line, never read (/dev/zero never
// ends; a directory used to read as an empty file).
TEST(DeviceConfig, RefusesWhatIsNotARegularFile) {
  const std::string dir = HAPCINE_BINARY_DIR;
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    try {
      ReadSeatConfigFile(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad + (bad == dir ? ": is a directory" : ": not a regular file"));
    }
  }
}

}  // namespace
}  // namespace hapcine
