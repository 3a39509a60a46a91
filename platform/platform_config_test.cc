#include "platform/platform_config.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

std::string Slurp(const std::string& rel) {
  std::ifstream in(std::string(HAPCINE_SOURCE_DIR) + "/" + rel);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(PlatformConfig, ExampleFilesLoad) {
  const PlatformConfig seat = ParsePlatformJson(Slurp("haptics/platform_3dof.json"), "3dof");
  EXPECT_EQ(seat.NumEnabled(), 3);
  EXPECT_TRUE(seat.enabled[static_cast<int>(Dof::kHeave)]);
  EXPECT_FALSE(seat.enabled[static_cast<int>(Dof::kSway)]);
  EXPECT_NEAR(seat.limits[static_cast<int>(Dof::kPitch)].position, DegToRad(8), 1e-12);
  EXPECT_FALSE(seat.stewart.has_value());
  const PlatformConfig hexapod = ParsePlatformJson(Slurp("haptics/platform_stewart.json"), "6dof");
  EXPECT_EQ(hexapod.NumEnabled(), 6);
  ASSERT_TRUE(hexapod.stewart.has_value());
}

TEST(PlatformConfig, HapSeatFilesAreNotPlatforms) {
  EXPECT_FALSE(IsPlatformJson(Slurp("haptics/hapseat.json")));
  EXPECT_TRUE(IsPlatformJson(Slurp("haptics/platform_3dof.json")));
  EXPECT_FALSE(IsPlatformJson("not json"));
  EXPECT_FALSE(IsPlatformJson("{\"type\": 3}"));
}

TEST(PlatformConfig, JsonRoundTrip) {
  const PlatformConfig a = ParsePlatformJson(Slurp("haptics/platform_stewart.json"), "6dof");
  const PlatformConfig b = ParsePlatformJson(PlatformConfigToJson(a), "again");
  EXPECT_EQ(PlatformConfigToJson(a), PlatformConfigToJson(b));
  for (int d = 0; d < kNumDofs; ++d) {
    EXPECT_NEAR(a.limits[d].velocity, b.limits[d].velocity, 1e-12);
  }
  EXPECT_NEAR(a.cueing.tilt_rate_rad_s, DegToRad(3), 1e-12);
}

TEST(PlatformConfig, RejectsBadFilesNamingTheProblem) {
  const std::string ok_dof = "\"heave\": {\"position\": 0.05, \"velocity\": 0.2, \"acceleration\": 2}";
  auto parse = [](const std::string& text) { return ParsePlatformJson(text, "p.json"); };
  const std::pair<std::string, std::string> cases[] = {
      {"{\"type\": \"platform\"}", "no degree of freedom"},
      {"{\"type\": \"platform\", \"dofs\": {\"jump\": {}}}", "unknown degree of freedom 'jump'"},
      {"{\"type\": \"platform\", \"dofs\": {\"heave\": {\"position\": 0.05}}}", "needs position, velocity"},
      {"{\"type\": \"platform\", \"dofs\": {" + ok_dof + "}, \"colour\": 1}", "unknown key 'colour'"},
      {"{\"type\": \"platform\", \"dofs\": {\"heave\": {\"position\": -1, \"velocity\": 1, "
       "\"acceleration\": 1}}}", "limits of heave"},
      {"{\"type\": \"platform\", \"dofs\": {" + ok_dof + "}, \"cueing\": {\"tilt_max_deg\": 80}}",
       "tilt_max_deg"},
      {"{\"type\": \"platform\", \"dofs\": {" + ok_dof + "}, \"stewart\": {\"min_leg_m\": 1}}",
       "'stewart' needs"},
      {"{\"type\": \"platform\", \"dofs\": {" + ok_dof + "}, \"rate_hz\": 1}", "rate_hz"},
      {"{\"type\": \"platform\", ", "not valid JSON"},
  };
  for (const auto& [text, reason] : cases) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
}

TEST(PlatformConfig, RejectsALegStrokeThatExcludesHome) {
  std::string text = Slurp("haptics/platform_stewart.json");
  const auto at = text.find("\"min_leg_m\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find(',', at) - at, "\"min_leg_m\": 0.6");  // home legs are 0.54 m
  EXPECT_THROW(ParsePlatformJson(text, "p.json"), Error);
}

}  // namespace
}  // namespace hapcine
