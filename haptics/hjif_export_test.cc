#include "haptics/hjif_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "haptics/haptic_models.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine {
namespace {

HapticTrack Track() {
  HapticOptions o;
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

TEST(HjifExport, RejectsEmptyTracksAndBadOptions) {
  EXPECT_ANY_THROW(HapticTrackToHjif(HapticTrack(), HjifOptions()));
  HjifOptions o;
  o.keyframe_rate_hz = 0;
  EXPECT_ANY_THROW(HapticTrackToHjif(Track(), o));
}

}  // namespace
}  // namespace hapcine
