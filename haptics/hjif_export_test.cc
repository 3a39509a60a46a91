#include "haptics/hjif_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "haptics/haptic_models.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

HapticTrack Track() {
  HapticOptions o;
  o.rate_hz = 1000;  // the tests index rows by millisecond
  o.source = "clip.camera.csv";
  return MakeHapticTrack(testing::MakeEffectPath(CameraEffect::kDutchAngle), o);
}

TEST(HjifExport, StructureAndValues) {
  const HapticTrack track = Track();
  HjifOptions o;
  o.date = "2026-01-02";
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/hjif_export_test.hjif";
  WriteHjifFile(track, file, o);
  std::ifstream in(file);
  const nlohmann::json j = nlohmann::json::parse(in);
  std::remove(file.c_str());
  EXPECT_EQ(j.at("profile"), "Main");
  EXPECT_EQ(j.at("version"), "2023");
  EXPECT_EQ(j.at("date"), "2026-01-02");
  EXPECT_EQ(j.at("timescale"), 1000);
  ASSERT_EQ(j.at("perceptions").size(), 3u);
  const size_t expected_keys = 701;  // 7 s at 100 Hz, both ends
  for (int a = 0; a < 3; ++a) {
    const auto& p = j["perceptions"][a];
    EXPECT_EQ(p.at("perception_modality"), "Position");
    EXPECT_EQ(p.at("id"), a);
    ASSERT_EQ(p.at("channels").size(), 3u);
    for (int k = 0; k < 3; ++k) {
      const auto& ch = p["channels"][k];
      const double gain = ch.at("gain");
      const auto& band = ch.at("bands").at(0);
      EXPECT_EQ(band.at("band_type"), "Curve");
      const auto& effect = band.at("effects").at(0);
      EXPECT_EQ(effect.at("effect_type"), "Basis");
      const auto& keys = effect.at("keyframes");
      ASSERT_EQ(keys.size(), expected_keys);
      long long prev = -1;
      for (const auto& key : keys) {
        const long long rel = key.at("relative_position");
        EXPECT_GT(rel, prev);
        prev = rel;
        const double t = (effect.at("position").get<long long>() + rel) / 1000.0;
        const HapticSample& s = track.samples[static_cast<size_t>(std::lround(t * 1000))];
        EXPECT_NEAR(key.at("amplitude_modulation").get<double>() * gain, s.pos_m[a][k], 1e-12);
        EXPECT_LE(std::abs(key.at("amplitude_modulation").get<double>()), 1.0);
      }
    }
  }
  // The dutch angle moves the right hand's y: the keyframes are not all zero.
  double m = 0;
  for (const auto& key :
       j["perceptions"][2]["channels"][1]["bands"][0]["effects"][0]["keyframes"]) {
    m = std::max(m, std::abs(key["amplitude_modulation"].get<double>()));
  }
  EXPECT_GT(m, 0.3);
}

// The members, and their JSON types, that the MPEG reference software's HJIF
// loader (IOJson::loadFile and the load* functions it calls) requires; a
// file missing one is not loaded. Also the enumerations it maps names with.
TEST(HjifExport, HasEveryMemberTheReferenceLoaderRequires) {
  const nlohmann::json j = HapticTrackToHjif(Track(), HjifOptions{});
  auto has = [](const nlohmann::json& o, const char* key, bool (nlohmann::json::*is)() const) {
    EXPECT_TRUE(o.contains(key) && (o.at(key).*is)()) << key << " in " << o.dump().substr(0, 80);
  };
  using J = nlohmann::json;
  for (const char* k : {"version", "profile", "date", "description"}) has(j, k, &J::is_string);
  // (rapidjson's IsUint: a non-negative integer)
  has(j, "level", &J::is_number_integer);
  has(j, "timescale", &J::is_number_integer);
  EXPECT_GE(j["level"].get<int>(), 0);
  EXPECT_GT(j["timescale"].get<int>(), 0);
  for (const char* k : {"perceptions", "avatars", "syncs"}) has(j, k, &J::is_array);
  for (const auto& av : j["avatars"]) {
    has(av, "id", &J::is_number_integer);
    has(av, "lod", &J::is_number_integer);
    EXPECT_EQ(av.at("type"), "Custom");
  }
  for (const auto& p : j["perceptions"]) {
    has(p, "id", &J::is_number_integer);
    has(p, "avatar_id", &J::is_number_integer);
    has(p, "description", &J::is_string);
    EXPECT_EQ(p.at("perception_modality"), "Position");
    has(p, "channels", &J::is_array);
    has(p, "effect_library", &J::is_array);
    for (const auto& d : p.at("reference_devices")) {
      has(d, "id", &J::is_number_integer);
      has(d, "name", &J::is_string);
    }
    for (const auto& ch : p["channels"]) {
      has(ch, "id", &J::is_number_integer);
      has(ch, "description", &J::is_string);
      has(ch, "gain", &J::is_number);
      has(ch, "mixing_coefficient", &J::is_number);
      has(ch, "body_part_mask", &J::is_number_integer);
      EXPECT_GE(ch["body_part_mask"].get<int>(), 0);
      has(ch, "bands", &J::is_array);
      for (const auto& part : ch.at("body_part_target")) {
        EXPECT_TRUE(part == "Head" || part == "Left" || part == "Right" || part == "Hand") << part;
      }
      for (const char* axis : {"X", "Y", "Z"}) {
        EXPECT_TRUE(ch.at("direction").at(axis).is_number_integer()) << axis;
      }
      for (const auto& band : ch["bands"]) {
        EXPECT_EQ(band.at("band_type"), "Curve");
        EXPECT_EQ(band.at("curve_type"), "Linear");
        has(band, "lower_frequency_limit", &J::is_number_integer);
        has(band, "upper_frequency_limit", &J::is_number_integer);
        has(band, "effects", &J::is_array);
        for (const auto& e : band["effects"]) {
          EXPECT_EQ(e.at("effect_type"), "Basis");
          has(e, "position", &J::is_number_integer);
          has(e, "phase", &J::is_number);
          EXPECT_EQ(e.at("base_signal"), "Sine");
          has(e, "keyframes", &J::is_array);
          for (const auto& key : e["keyframes"]) {
            ASSERT_TRUE(key.at("relative_position").is_number_integer());
            ASSERT_TRUE(key.at("amplitude_modulation").is_number());
          }
        }
      }
    }
  }
  // Each channel's direction is its seat axis.
  const auto& right = j["perceptions"][2];
  EXPECT_EQ(right["channels"][1]["direction"]["Y"], 1);
  EXPECT_EQ(right["channels"][1]["direction"]["X"], 0);
  EXPECT_EQ(right["channels"][0]["body_part_target"], nlohmann::json::array({"Right", "Hand"}));
}

// The streaming writer prints the very text of the document's dump(1).
TEST(HjifExport, StreamedTextIsTheDocumentsDump) {
  HjifOptions o;
  o.date = "2026-01-02";
  HapticTrack track = Track();
  track.source = "odd \"name\"\n\\ \"keyframes\": \"\x01.csv";
  for (double rate : {100.0, 7.0}) {
    o.keyframe_rate_hz = rate;
    std::ostringstream streamed;
    WriteHjif(track, o, streamed);
    EXPECT_EQ(streamed.str(), HapticTrackToHjif(track, o).dump(1) + "\n") << rate;
  }
  HapticTrack one;
  one.samples.resize(1);
  one.samples[0].pos_m[1] = {0.01, -0.02, 0.003};
  std::ostringstream streamed;
  WriteHjif(one, o, streamed);
  EXPECT_EQ(streamed.str(), HapticTrackToHjif(one, o).dump(1) + "\n");
}

TEST(HjifExport, RejectsEmptyTracksAndBadOptions) {
  EXPECT_ANY_THROW(HapticTrackToHjif(HapticTrack(), HjifOptions()));
  HjifOptions o;
  o.keyframe_rate_hz = 0;
  EXPECT_ANY_THROW(HapticTrackToHjif(Track(), o));
}

}  // namespace
}  // namespace hapcine
