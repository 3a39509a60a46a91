#include "haptics/haptic_edits.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

const char* kFullExample = R"({
  "format": "hapcine-edits",
  "version": 1,
  "revision": 3,
  "shots": [
    {"shot": 2, "gain": 0.5},
    {"shot": 0, "model": "semantic", "gain": 0.5, "mute": false,
     "washout": {"mode": "adaptive", "return_accel_m_s2": 0.05, "window_s": 4,
                 "tau_s": 2, "order": 2}}
  ],
  "keyframes": [
    {"start_s": 1.0, "end_s": 2.5, "effect": "zoom_in", "intensity": 0.8},
    {"start_s": 3, "end_s": 4, "effect": "crab_walk", "intensity": -1}
  ],
  "x-studio": {"zoom": [0, 12.5]}
})";

TEST(HapticEdits, ParsesEveryField) {
  const HapticEdits e = ParseHapticEdits(kFullExample, "film.edits.json");
  EXPECT_EQ(e.revision, 3);
  ASSERT_EQ(e.shots.size(), 2u);
  EXPECT_EQ(e.shots[0].shot, 0);  // sorted by shot
  EXPECT_EQ(e.shots[1].shot, 2);
  EXPECT_EQ(e.shots[0].model, HapticModel::kSemantic);
  EXPECT_EQ(e.shots[0].gain, 0.5);
  EXPECT_EQ(e.shots[0].mute, false);
  ASSERT_TRUE(e.shots[0].washout);
  EXPECT_EQ(e.shots[0].washout->mode, "adaptive");
  EXPECT_EQ(e.shots[0].washout->return_accel_m_s2, 0.05);
  EXPECT_EQ(e.shots[0].washout->window_s, 4.0);
  EXPECT_EQ(e.shots[0].washout->tau_s, 2.0);
  EXPECT_EQ(e.shots[0].washout->order, 2);
  EXPECT_FALSE(e.shots[1].model);
  EXPECT_FALSE(e.shots[1].mute);
  EXPECT_FALSE(e.shots[1].washout);
  ASSERT_TRUE(e.keyframes);
  ASSERT_EQ(e.keyframes->size(), 2u);
  EXPECT_EQ((*e.keyframes)[0].effect, CameraEffect::kZoomIn);
  EXPECT_EQ((*e.keyframes)[0].intensity, 0.8);
  EXPECT_EQ((*e.keyframes)[1].effect, CameraEffect::kTraveling);  // by its Table 2 name
  EXPECT_EQ((*e.keyframes)[1].start_s, 3.0);
  EXPECT_EQ(e.extensions.at("x-studio"), R"({"zoom":[0,12.5]})");
  EXPECT_FALSE(e.empty());
  EXPECT_EQ(e.FindShot(2), &e.shots[1]);
  EXPECT_EQ(e.FindShot(1), nullptr);
}

TEST(HapticEdits, MinimalFileIsEmpty) {
  const HapticEdits e = ParseHapticEdits(R"({"format":"hapcine-edits","version":1})", "f");
  EXPECT_TRUE(e.empty());
  EXPECT_EQ(e.revision, 0);
  // An empty keyframe list is not "absent": it replaces the classifier by nothing.
  const HapticEdits k =
      ParseHapticEdits(R"({"format":"hapcine-edits","version":1,"keyframes":[]})", "f");
  EXPECT_FALSE(k.empty());
  EXPECT_TRUE(k.keyframes && k.keyframes->empty());
}

TEST(HapticEdits, RoundTripIsStableAndPretty) {
  const HapticEdits e = ParseHapticEdits(kFullExample, "f");
  const std::string text = HapticEditsToJson(e);
  EXPECT_EQ(ParseHapticEdits(text, "f"), e);
  EXPECT_EQ(HapticEditsToJson(ParseHapticEdits(text, "f")), text);  // a fixed point
  // The documented key order, two-space indent, a final newline.
  EXPECT_EQ(text.rfind("{\n  \"format\": \"hapcine-edits\",\n  \"version\": 1,\n  \"revision\": 3,\n",
                       0),
            0u)
      << text;
  EXPECT_LT(text.find("\"shots\""), text.find("\"keyframes\""));
  EXPECT_LT(text.find("\"keyframes\""), text.find("\"x-studio\""));
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find("\"effect\": \"traveling\""), std::string::npos);  // Table 1 name on write
}

// Every rejected input, with the field its one-line message must name.
struct BadCase {
  const char* json;
  const char* expected;  // a substring of the reason
};

std::string WithHeader(const std::string& body) {
  return R"({"format":"hapcine-edits","version":1)" + (body.empty() ? "" : "," + body) + "}";
}

TEST(HapticEdits, EveryParseErrorNamesItsField) {
  const std::vector<BadCase> cases = {
      {"{", "not valid JSON"},
      {"[1,2]", "an edits file is a JSON object"},
      {R"({"version":1})", "format: missing"},
      {R"({"format":"hapcine-seat","version":1})", "format: must be \"hapcine-edits\""},
      {R"({"format":"hapcine-edits"})", "version: missing"},
      {R"({"format":"hapcine-edits","version":2})", "version: 2 is not supported"},
      {R"({"format":"hapcine-edits","version":"1"})", "version: \"1\" is not supported"},
  };
  const std::vector<std::pair<std::string, std::string>> body_cases = {
      {R"("revison":1)", "revison: unknown key"},
      {R"("revision":-1)", "revision: must be in [0,"},
      {R"("revision":1.5)", "revision: must be an integer"},
      {R"("shots":{})", "shots: must be a list"},
      {R"("shots":[1])", "shots[0]: must be an object"},
      {R"("shots":[{"gain":1}])", "shots[0]: missing \"shot\""},
      {R"("shots":[{"shot":"1"}])", "shots[0].shot: must be an integer"},
      {R"("shots":[{"shot":0},{"shot":1,"gian":1}])", "shots[1].gian: unknown key"},
      {R"("shots":[{"shot":0,"model":"physical"}])", "shots[0].model: 'physical' is not"},
      {R"("shots":[{"shot":0,"gain":4.0001}])", "shots[0].gain: must be in [0, 4]"},
      {R"("shots":[{"shot":0,"gain":-0.1}])", "shots[0].gain: must be in [0, 4]"},
      {R"("shots":[{"shot":0,"gain":"2"}])", "shots[0].gain: must be a number"},
      {R"("shots":[{"shot":0,"gain":1e999}])", "not valid JSON"},
      {R"("shots":[{"shot":0,"mute":1}])", "shots[0].mute: must be true or false"},
      {R"("shots":[{"shot":3},{"shot":3,"gain":1}])", "shots: shot 3 is listed twice"},
      {R"("shots":[{"shot":0,"washout":"off"}])", "shots[0].washout: must be an object"},
      {R"("shots":[{"shot":0,"washout":{"mode":"lowpass"}}])", "shots[0].washout.mode: 'lowpass'"},
      {R"("shots":[{"shot":0,"washout":{"tau":2}}])", "shots[0].washout.tau: unknown key"},
      {R"("shots":[{"shot":0,"washout":{"tau_s":0.05}}])", "shots[0].washout.tau_s: must be in (0.05"},
      {R"("shots":[{"shot":0,"washout":{"order":3}}])", "shots[0].washout.order: must be in [1, 2]"},
      {R"("shots":[{"shot":0,"washout":{"window_s":0}}])", "shots[0].washout.window_s: must be in (0"},
      {R"("shots":[{"shot":0,"washout":{"return_accel_m_s2":101}}])",
       "shots[0].washout.return_accel_m_s2: must be in (0, 100]"},
      {R"("keyframes":{})", "keyframes: must be a list"},
      {R"("keyframes":[{"start_s":1,"effect":"zoom_in"}])", "keyframes[0]: missing \"end_s\""},
      {R"("keyframes":[{"start_s":2,"end_s":1,"effect":"zoom_in"}])", "keyframes[0].end_s: must be after"},
      {R"("keyframes":[{"start_s":-1,"end_s":1,"effect":"zoom_in"}])", "keyframes[0].start_s: must be in"},
      {R"("keyframes":[{"start_s":0,"end_s":1,"effect":"zoom"}])", "keyframes[0].effect: unknown effect 'zoom'"},
      {R"("keyframes":[{"start_s":0,"end_s":1,"effect":"none"}])", "keyframes[0].effect: unknown effect"},
      {R"("keyframes":[{"start_s":0,"end_s":1,"effect":"tilting","intensity":1.5}])",
       "keyframes[0].intensity: must be in [-1, 1]"},
      {R"("keyframes":[{"start_s":0,"end_s":2,"effect":"tilting"},{"start_s":1,"end_s":3,"effect":"arcing"}])",
       "keyframes[1].start_s: starts before the previous keyframe ends"},
      {R"("keyframes":[{"start_s":0,"end_s":1,"effect":"tilting","speed":2}])",
       "keyframes[0].speed: unknown key"},
      // Text from the file is shown on one line, control characters escaped.
      {R"("shots":[{"shot":0,"model":"semantic\nfoo"}])", "shots[0].model: 'semantic\\x0afoo' is not"},
      {R"("a\tb":1)", "a\\x09b: unknown key"},
      // Cut after 60 bytes, never inside a UTF-8 character (here 59 'a' then a 2-byte 'é').
      {R"("shots":[{"shot":0,"model":"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaéé"}])",
       "'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa...' is not"},
  };
  std::vector<BadCase> all = cases;
  std::vector<std::string> texts;
  for (const auto& [body, _] : body_cases) texts.push_back(WithHeader(body));
  for (size_t i = 0; i < body_cases.size(); ++i) all.push_back({texts[i].c_str(), body_cases[i].second.c_str()});
  for (const BadCase& c : all) {
    try {
      ParseHapticEdits(c.json, "film.edits.json");
      ADD_FAILURE() << "accepted " << c.json;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "film.edits.json");
      EXPECT_NE(e.reason().find(c.expected), std::string::npos)
          << c.json << "\n  gave: " << e.reason();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(HapticEdits, ExtensionKeysAreAcceptedEverywhere) {
  const HapticEdits e = ParseHapticEdits(
      WithHeader(R"("x-a":1,"shots":[{"shot":0,"x-note":"loud","washout":{"x-b":true}}],)"
                 R"("keyframes":[{"start_s":0,"end_s":1,"effect":"tilting","x-colour":"red"}])"),
      "f");
  EXPECT_EQ(e.extensions.size(), 1u);
  EXPECT_EQ(e.shots.size(), 1u);
}

TEST(HapticEdits, OversizedTextIsRefusedBeforeParsing) {
  std::string big = WithHeader(R"("x-pad":")" + std::string(kMaxEditsFileBytes, 'a') + "\"");
  try {
    ParseHapticEdits(big, "big.edits.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.reason(), "larger than 4 MiB");
  }
}

TEST(HapticEdits, FileRoundTripAndErrors) {
  const fs::path dir = fs::temp_directory_path() / ("hapcine_edits_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "film.edits.json").string();
  HapticEdits e = ParseHapticEdits(kFullExample, "f");
  e.revision = 4;
  WriteHapticEditsFile(e, path);
  EXPECT_EQ(ReadHapticEditsFile(path), e);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"film.edits.json"});  // no temporary left behind
  {
    std::ofstream big(path, std::ios::binary | std::ios::trunc);
    big << std::string(kMaxEditsFileBytes + 1, ' ');
  }
  EXPECT_THROW(
      {
        try {
          ReadHapticEditsFile(path);
        } catch (const Error& err) {
          EXPECT_EQ(err.where(), path);
          EXPECT_EQ(err.reason(), "larger than 4 MiB");
          throw;
        }
      },
      Error);
  EXPECT_THROW(ReadHapticEditsFile((dir / "missing.edits.json").string()), Error);
  EXPECT_THROW(ReadHapticEditsFile(dir.string()), Error);  // a directory
  fs::remove_all(dir);
}

TEST(HapticEdits, PathForFilm) {
  EXPECT_EQ(EditsPathForFilm("a/b/film.mp4"), "a/b/film.edits.json");
  EXPECT_EQ(EditsPathForFilm("a/b/film.camera.csv"), "a/b/film.edits.json");
  EXPECT_EQ(EditsPathForFilm("film.mkv"), "film.edits.json");
  EXPECT_EQ(EditsPathForFilm("/x/my.clip.v2.mov"), "/x/my.clip.v2.edits.json");
  EXPECT_EQ(EditsPathForFilm("/x/noext"), "/x/noext.edits.json");
}

}  // namespace
}  // namespace hapcine
