#include "haptics/hjif_import.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "haptics/haptic_models.h"
#include "haptics/hjif_export.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

using nlohmann::json;

HapticTrack Track() {
  HapticOptions o;
  o.rate_hz = 1000;  // the reader samples a .hjif at 1 kHz: one row per keyframe below
  o.source = "clip.camera.csv";
  return MakeHapticTrack(testing::MakeEffectPath(CameraEffect::kDutchAngle), o);
}

// The error message of reading `doc`, "" if it reads.
std::string Refusal(const json& doc) {
  try {
    HjifToHapticTrack(doc, "x.hjif");
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "x.hjif");
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);  // one line
    return e.reason();
  }
  return "";
}

// A small file as another tool might write it: a Position perception with
// body_part_target names, a negative direction, metres (exponent 0).
json OtherToolsFile() {
  json key0 = {{"relative_position", 0}, {"amplitude_modulation", 0.0}};
  json key1 = {{"relative_position", 500}, {"amplitude_modulation", 0.5}};
  json effect = {{"effect_type", "Basis"}, {"position", 1000}, {"keyframes", {key0, key1}}};
  json band = {{"band_type", "Curve"}, {"curve_type", "Linear"}, {"lower_frequency_limit", 0},
               {"upper_frequency_limit", 50}, {"effects", {effect}}};
  json ch = {{"id", 0}, {"description", ""}, {"gain", 0.02}, {"mixing_coefficient", 1},
             {"body_part_target", {"Left", "Hand"}},
             {"direction", {{"X", 0}, {"Y", 0}, {"Z", -127}}}, {"bands", {band}}};
  json p = {{"id", 0}, {"perception_modality", "Position"}, {"description", ""},
            {"avatar_id", 0}, {"effect_library", json::array()}, {"channels", {ch}}};
  return {{"version", "2023"}, {"profile", "Main"}, {"level", 1}, {"date", "2026-01-01"},
          {"description", "other"}, {"timescale", 1000}, {"avatars", json::array()},
          {"perceptions", {p}}};
}

// What hapcine writes reads back as the track, at every keyframe.
TEST(HjifImport, ReadsBackWhatTheExporterWrites) {
  const HapticTrack track = Track();
  HjifOptions o;
  o.keyframe_rate_hz = 1000;  // a keyframe per sample: the curve is the track
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/hjif_import_test.hjif";
  WriteHjifFile(track, file, o);
  const HapticTrack back = ReadAnyHapticTrackFile(file);
  std::remove(file.c_str());
  EXPECT_EQ(back.model, "hjif");
  EXPECT_EQ(back.source, file);
  ASSERT_EQ(back.samples.size(), track.samples.size());
  for (size_t i = 0; i < track.samples.size(); ++i) {
    EXPECT_NEAR(back.samples[i].time_s, track.samples[i].time_s, 1e-9);
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_LT((back.samples[i].pos_m[a] - track.samples[i].pos_m[a]).norm(), 1e-12) << i;
    }
  }
}

// A film split into several effects reads back without a seam.
TEST(HjifImport, EffectsSharingABoundaryKeyframeMakeOneCurve) {
  HapticTrack track;
  for (int i = 0; i <= 2000; ++i) {  // 200 s at 10 Hz
    track.samples.emplace_back();
    track.samples.back().time_s = i / 10.0;
    track.samples.back().pos_m[2] = {0, 0.03 * std::sin(i * 0.01), 0};
  }
  HjifOptions o;
  o.keyframe_rate_hz = 10;
  const json doc = HapticTrackToHjif(track, o);
  ASSERT_GT(doc["perceptions"][2]["channels"][1]["bands"][0]["effects"].size(), 1u);
  const HapticTrack back = HjifToHapticTrack(doc, "film.hjif", 10);
  ASSERT_EQ(back.samples.size(), track.samples.size());
  for (size_t i = 0; i < track.samples.size(); ++i) {
    EXPECT_NEAR(back.samples[i].pos_m[2].y(), track.samples[i].pos_m[2].y(), 1e-12) << i;
  }
}

TEST(HjifImport, ReadsAnotherToolsPositionFile) {
  const HapticTrack t = HjifToHapticTrack(OtherToolsFile(), "x.hjif", 1000);
  ASSERT_EQ(t.samples.size(), 501u);  // 1.0 .. 1.5 s
  EXPECT_DOUBLE_EQ(t.samples.front().time_s, 1.0);
  // Left hand, -Z: 0.5 x 0.02 m along -Z at the end, half of it halfway.
  EXPECT_NEAR(t.samples.back().pos_m[1].z(), -0.01, 1e-12);
  EXPECT_NEAR(t.samples[250].pos_m[1].z(), -0.005, 1e-12);
  EXPECT_EQ(t.samples.back().pos_m[0].norm(), 0);
}

// The reference software's body model: a palm alone is that hand.
TEST(HjifImport, BodyPartMaskOfAHandsPartIsThatHand) {
  json doc = OtherToolsFile();
  doc["perceptions"][0]["channels"][0].erase("body_part_target");
  doc["perceptions"][0]["channels"][0]["body_part_mask"] = 0x00020000;  // LEFT_HAND_PALM
  const HapticTrack left = HjifToHapticTrack(doc, "x.hjif", 1000);
  EXPECT_NEAR(left.samples.back().pos_m[1].z(), -0.01, 1e-12);
  doc["perceptions"][0]["channels"][0]["body_part_mask"] = 0x00010000;  // RIGHT_HAND_PALM
  const HapticTrack right = HjifToHapticTrack(doc, "x.hjif", 1000);
  EXPECT_NEAR(right.samples.back().pos_m[2].z(), -0.01, 1e-12);
  EXPECT_EQ(right.samples.back().pos_m[1].norm(), 0);
}

TEST(HjifImport, RefusesWhatItCannotPlayWithOneLineNamingIt) {
  json doc = OtherToolsFile();
  EXPECT_EQ(Refusal(doc), "");
  const json ch = doc["perceptions"][0]["channels"][0];
  auto refused_for = [&](const json& d, const std::string& what) {
    const std::string m = Refusal(d);
    EXPECT_NE(m.find(what), std::string::npos) << m;
  };
  json d = doc;
  d["perceptions"][0]["perception_modality"] = "Vibrotactile";
  refused_for(d, "perception 0 (Vibrotactile): only Position perceptions");
  d = doc;
  d["perceptions"][0]["channels"][0]["bands"][0]["curve_type"] = "Cubic";
  refused_for(d, "curve type Cubic unsupported");
  d = doc;
  d["perceptions"][0]["channels"][0]["bands"][0]["band_type"] = "Transient";
  refused_for(d, "band type Transient unsupported");
  d = doc;
  d["perceptions"][0]["channels"][0]["direction"] = {{"X", 90}, {"Y", 90}, {"Z", 0}};
  refused_for(d, "is not along X, Y or Z");
  d = doc;
  d["perceptions"][0]["channels"][0].erase("direction");
  refused_for(d, "no direction");
  d = doc;
  d["perceptions"][0]["channels"][0]["body_part_target"] = {"Leg"};
  refused_for(d, "is not the head, the left hand or the right hand");
  d = doc;
  d["perceptions"][0]["channels"][0].erase("body_part_target");
  d["perceptions"][0]["channels"][0]["body_part_mask"] = 0;
  refused_for(d, "body_part_mask 0 is not the head");
  d["perceptions"][0]["channels"][0]["body_part_mask"] = 0x2000F;  // the head and a palm
  refused_for(d, "body_part_mask 131087 is not the head");
  d = doc;
  d["perceptions"][0]["channels"].push_back(ch);
  refused_for(d, "a second channel for the left z axis");
  d = doc;
  json& effects = d["perceptions"][0]["channels"][0]["bands"][0]["effects"];
  effects.push_back(effects[0]);
  effects[1]["position"] = 1200;  // starts inside the first one
  refused_for(d, "keyframes overlap");
  d = doc;
  d["perceptions"][0]["channels"][0]["bands"][0]["effects"][0]["effect_type"] = "Reference";
  refused_for(d, "effect type Reference unsupported");
  d = doc;
  d["perceptions"][0]["channels"][0]["gain"] = 10;  // 5 m
  refused_for(d, "beyond 1 m");
  refused_for(json::array(), "not an MPEG-I Haptics");
  refused_for(json::object(), "no perceptions");
}

TEST(HjifImport, ChoosesTheReaderByExtension) {
  EXPECT_TRUE(IsHjifPath("a/b.hjif"));
  EXPECT_TRUE(IsHjifPath("B.HJIF"));
  EXPECT_FALSE(IsHjifPath("b.haptic.csv"));
  EXPECT_FALSE(IsHjifPath("hjif"));
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/hjif_import_test_bad.hjif";
  std::ofstream(file) << "{ not json";
  try {
    ReadAnyHapticTrackFile(file);
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not JSON"), std::string::npos) << e.what();
  }
  std::remove(file.c_str());
}

}  // namespace
}  // namespace hapcine
