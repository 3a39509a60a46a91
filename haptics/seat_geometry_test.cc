#include "haptics/seat_geometry.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(SeatGeometry, DefaultsArePlausibleAndValid) {
  SeatGeometry s;
  EXPECT_NO_THROW(s.Check());
  EXPECT_GT(s.rest_m[0].y(), 0.3);  // head well above the chest
  EXPECT_LT(s.rest_m[1].x(), 0);    // left hand on the left
  EXPECT_GT(s.rest_m[2].x(), 0);    // right hand on the right
  EXPECT_DOUBLE_EQ(s.workspace_half_m, 0.05);
  EXPECT_LT(s.usable_half_m, s.clamp_half_m);
  EXPECT_DOUBLE_EQ(s.rate_hz, 100);  // stored; the player interpolates to 1 kHz
}

TEST(SeatGeometry, JsonOverridesOnlyWhatItNames) {
  const SeatGeometry s = ParseSeatGeometryJson(
      R"({"head_m": [0, 0.5, 0.1], "usable_half_m": 0.04, "comment": "mine"})", "seat.json");
  EXPECT_DOUBLE_EQ(s.rest_m[0].y(), 0.5);
  EXPECT_DOUBLE_EQ(s.usable_half_m, 0.04);
  EXPECT_DOUBLE_EQ(s.rest_m[1].x(), SeatGeometry().rest_m[1].x());
}

TEST(SeatGeometry, RoundTripsThroughJson) {
  SeatGeometry s;
  s.center_m = Eigen::Vector3d(0.01, 0.02, 0.03);
  s.rate_hz = 500;
  const SeatGeometry r = ParseSeatGeometryJson(SeatGeometryToJson(s), "x");
  EXPECT_TRUE(r.center_m.isApprox(s.center_m));
  EXPECT_DOUBLE_EQ(r.rate_hz, 500);
}

TEST(SeatGeometry, RejectsBadInput) {
  EXPECT_THROW(ParseSeatGeometryJson("{", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson("[1]", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson(R"({"hed_m": [0,0,0]})", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson(R"({"head_m": [0,0]})", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson(R"({"head_m": [0,"a",0]})", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson(R"({"usable_half_m": 0.2})", "s.json"), Error);
  EXPECT_THROW(ParseSeatGeometryJson(R"({"rate_hz": 0})", "s.json"), Error);
  // An actuator at the centre cannot render rotations.
  EXPECT_THROW(ParseSeatGeometryJson(R"({"head_m": [0,0,0]})", "s.json"), Error);
  try {
    ParseSeatGeometryJson(R"({"hed_m": 1})", "my_seat.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("my_seat.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("hed_m"), std::string::npos);
  }
  EXPECT_THROW(LoadSeatGeometryFile("/nonexistent/seat.json"), Error);
}

// A number beyond double's range is nlohmann's out_of_range, not a
// parse_error; it must still be a one-line Error naming the file (found by
// fuzz/seat_json_fuzzer).
TEST(SeatGeometry, NumberOverflowIsAnErrorNamingTheFile) {
  try {
    ParseSeatGeometryJson(R"({"rate_hz": 1e400})", "my_seat.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "my_seat.json");
    EXPECT_NE(e.reason().find("not valid JSON"), std::string::npos) << e.reason();
  }
}

// The documented configuration file in the source tree is exactly the
// built-in defaults (so neither can drift from the other).
TEST(SeatGeometry, ShippedConfigurationFileIsTheDefaults) {
  const SeatGeometry file =
      LoadSeatGeometryFile(std::string(HAPCINE_SOURCE_DIR) + "/haptics/hapseat.json");
  EXPECT_EQ(SeatGeometryToJson(file), SeatGeometryToJson(SeatGeometry{}));
}

TEST(SeatGeometry, LoadsFile) {
  const std::string path = std::string(HAPCINE_BINARY_DIR) + "/seat_geometry_test.json";
  {
    std::ofstream out(path);
    out << R"({"rate_hz": 250})";
  }
  EXPECT_DOUBLE_EQ(LoadSeatGeometryFile(path).rate_hz, 250);
  std::remove(path.c_str());
}

// Not a regular file: refused with one line, never read (/dev/zero never
// ends; a directory used to read as an empty file).
TEST(SeatGeometry, RefusesWhatIsNotARegularFile) {
  const std::string dir = HAPCINE_BINARY_DIR;
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    try {
      LoadSeatGeometryFile(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad + (bad == dir ? ": is a directory" : ": not a regular file"));
    }
  }
}

}  // namespace
}  // namespace hapcine
