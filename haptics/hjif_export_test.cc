#include "haptics/hjif_export.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

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

// Every keyframe of channel (a, k), with its absolute tick.
std::vector<std::pair<long long, double>> ChannelKeyframes(const nlohmann::json& j, int a, int k) {
  std::vector<std::pair<long long, double>> keys;
  for (const auto& e : j["perceptions"][a]["channels"][k]["bands"][0]["effects"]) {
    for (const auto& key : e.at("keyframes")) {
      keys.emplace_back(e.at("position").get<long long>() + key.at("relative_position").get<long long>(),
                        key.at("amplitude_modulation").get<double>());
    }
  }
  return keys;
}

TEST(HjifExport, StructureAndValues) {
  const HapticTrack track = Track();
  HjifOptions o;
  o.date = "2026-01-02T03:04:05Z";
  const std::string file = std::string(HAPCINE_BINARY_DIR) + "/hjif_export_test.hjif";
  WriteHjifFile(track, file, o);
  std::ifstream in(file);
  const nlohmann::json j = nlohmann::json::parse(in);
  std::remove(file.c_str());
  EXPECT_EQ(j.at("profile"), "Main");
  EXPECT_EQ(j.at("version"), "2023");
  EXPECT_EQ(j.at("date"), "2026-01-02T03:04:05Z");
  EXPECT_EQ(j.at("timescale"), 1000);
  EXPECT_EQ(j.at("description"), "clip.camera");  // the source's stem, not its path
  ASSERT_EQ(j.at("perceptions").size(), 3u);
  const size_t expected_keys = 701;  // 7 s at 100 Hz, both ends
  for (int a = 0; a < 3; ++a) {
    const auto& p = j["perceptions"][a];
    EXPECT_EQ(p.at("perception_modality"), "Position");
    EXPECT_EQ(p.at("unit_exponent"), -3);             // time: ms ticks
    EXPECT_EQ(p.at("perception_unit_exponent"), -3);  // amplitude x gain: mm
    ASSERT_EQ(p.at("channels").size(), 3u);
    for (int k = 0; k < 3; ++k) {
      const auto& ch = p["channels"][k];
      EXPECT_EQ(ch.at("gain"), 50.0);
      EXPECT_EQ(ch.at("body_part_mask"), HjifBodyPartMask(static_cast<Actuator>(a)));
      const auto& band = ch.at("bands").at(0);
      EXPECT_EQ(band.at("band_type"), "Curve");
      ASSERT_EQ(band.at("effects").size(), 1u);  // 7 s: one effect
      const auto keys = ChannelKeyframes(j, a, k);
      ASSERT_EQ(keys.size(), expected_keys);
      long long prev = -1;
      for (const auto& [tick, amplitude] : keys) {
        EXPECT_GT(tick, prev);
        prev = tick;
        const HapticSample& s = track.samples[static_cast<size_t>(tick)];
        EXPECT_NEAR(amplitude * 50 * 1e-3, s.pos_m[a][k], 1e-12);
        EXPECT_LE(std::abs(amplitude), 1.0);
      }
    }
  }
  // The dutch angle moves the right hand's y: the keyframes are not all zero.
  double m = 0;
  for (const auto& key : ChannelKeyframes(j, 2, 1)) m = std::max(m, std::abs(key.second));
  EXPECT_GT(m, 0.3);
}

// A film: no effect spans more than the binary format's 16-bit relative
// position; consecutive effects share their boundary keyframe, so the curve
// is the same as one long effect's.
TEST(HjifExport, LongTracksAreSplitIntoEffectsOf65535TicksAtMost) {
  HapticTrack track;
  track.source = "/some/dir/film.camera.csv";
  track.rate_hz = 100;
  for (int i = 0; i <= 20000; ++i) {  // 200 s
    HapticSample s;
    s.time_s = i / 100.0;
    s.pos_m[1] = {0.04 * std::sin(i * 1e-3), 0, 0};
    track.samples.push_back(s);
  }
  HjifOptions o;
  o.keyframe_rate_hz = 10;
  const nlohmann::json j = HapticTrackToHjif(track, o);
  const auto& effects = j["perceptions"][1]["channels"][0]["bands"][0]["effects"];
  ASSERT_EQ(effects.size(), 4u);  // 200 s in effects of <= 65.5 s
  long long end = 0;
  for (const auto& e : effects) {
    EXPECT_EQ(e.at("position").get<long long>(), end);  // starts where the previous ended
    EXPECT_EQ(e.at("keyframes").at(0).at("relative_position"), 0);
    const long long last = e.at("keyframes").back().at("relative_position");
    EXPECT_LE(last, kHjifMaxRelativePosition);
    end = e.at("position").get<long long>() + last;
  }
  EXPECT_EQ(end, 200000);
  for (const auto& [tick, amplitude] : ChannelKeyframes(j, 1, 0)) {
    EXPECT_NEAR(amplitude * 50e-3, 0.04 * std::sin(tick * 1e-4), 1e-12) << tick;
  }
}

TEST(HjifExport, DescriptionIsShortAndUtf8) {
  EXPECT_EQ(HjifShortText("abc", 255), "abc");
  EXPECT_EQ(HjifShortText(std::string(300, 'x'), 255).size(), 255u);
  // Cut on a character boundary: "é" is two bytes.
  EXPECT_EQ(HjifShortText("a\xc3\xa9", 2), "a");
  EXPECT_EQ(HjifShortText("a\xc3\xa9", 3), "a\xc3\xa9");
  EXPECT_EQ(HjifShortText("a\xff\nb", 255), "a??b");
  HapticTrack track = Track();
  track.source = "/a/long/path/" + std::string(400, 'n') + ".camera.csv";
  const nlohmann::json j = HapticTrackToHjif(track, HjifOptions{});
  EXPECT_EQ(j.at("description").get<std::string>(), std::string(255, 'n'));
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
    EXPECT_GE(av.at("id").get<int>(), 1);  // 0 is reserved
    EXPECT_EQ(av.at("type"), "Custom");
    has(av, "mesh", &J::is_string);  // a Custom avatar's mesh: needed by the binary format
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
      EXPECT_GE(d.at("id").get<int>(), 1);
      has(d, "name", &J::is_string);
    }
    for (const auto& ch : p["channels"]) {
      has(ch, "id", &J::is_number_integer);
      has(ch, "description", &J::is_string);
      has(ch, "gain", &J::is_number);
      has(ch, "mixing_coefficient", &J::is_number);
      has(ch, "body_part_mask", &J::is_number_integer);
      EXPECT_GT(ch["body_part_mask"].get<int>(), 0);
      has(ch, "bands", &J::is_array);
      // The body part is the mask's: the binary format keeps a mask or a
      // target, not both.
      EXPECT_FALSE(ch.contains("body_part_target"));
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
          // Meaningless in a Curve band: the reference writer drops them.
          EXPECT_FALSE(e.contains("id") || e.contains("phase") || e.contains("base_signal"));
          has(e, "keyframes", &J::is_array);
          for (const auto& key : e["keyframes"]) {
            ASSERT_TRUE(key.at("relative_position").is_number_integer());
            ASSERT_TRUE(key.at("amplitude_modulation").is_number());
          }
        }
      }
    }
  }
  // Each channel's direction is its seat axis, an int8 unit vector (127).
  const auto& right = j["perceptions"][2];
  EXPECT_EQ(right["channels"][1]["direction"]["Y"], 127);
  EXPECT_EQ(right["channels"][1]["direction"]["X"], 0);
  EXPECT_EQ(right["channels"][0]["body_part_mask"], HjifBodyPartMask(Actuator::kRight));
  EXPECT_NE(HjifBodyPartMask(Actuator::kRight), HjifBodyPartMask(Actuator::kLeft));
  // ISO 8601 date-time (the schema's "date-time"), UTC.
  const std::string date = j["date"];
  EXPECT_EQ(date.size(), 20u) << date;
  EXPECT_EQ(date[10], 'T');
  EXPECT_EQ(date.substr(10), "T00:00:00Z");  // the day only: the same track made twice is the same file
}

// SOURCE_DATE_EPOCH (reproducible builds) fixes the day written.
TEST(HjifExport, SourceDateEpochFixesTheDate) {
  ::setenv("SOURCE_DATE_EPOCH", "86400", 1);  // 1970-01-02
  const nlohmann::json j = HapticTrackToHjif(Track(), HjifOptions());
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(j.at("date"), "1970-01-02T00:00:00Z");
}

// The streaming writer prints the very text of the document's dump(1).
TEST(HjifExport, StreamedTextIsTheDocumentsDump) {
  HjifOptions o;
  o.date = "2026-01-02T00:00:00Z";
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
  // Several effects per channel (150 s).
  HapticTrack film;
  for (int i = 0; i <= 1500; ++i) {
    film.samples.emplace_back();
    film.samples.back().time_s = i / 10.0;
    film.samples.back().pos_m[0] = {0.001 * (i % 7), 0, -0.002};
  }
  o.keyframe_rate_hz = 10;
  std::ostringstream streamed_film;
  WriteHjif(film, o, streamed_film);
  const nlohmann::json doc = HapticTrackToHjif(film, o);
  EXPECT_EQ(doc["perceptions"][0]["channels"][0]["bands"][0]["effects"].size(), 3u);
  EXPECT_EQ(streamed_film.str(), doc.dump(1) + "\n");
}

TEST(HjifExport, RejectsEmptyTracksAndBadOptions) {
  EXPECT_ANY_THROW(HapticTrackToHjif(HapticTrack(), HjifOptions()));
  HjifOptions o;
  o.keyframe_rate_hz = 0;
  EXPECT_ANY_THROW(HapticTrackToHjif(Track(), o));
}

}  // namespace
}  // namespace hapcine
