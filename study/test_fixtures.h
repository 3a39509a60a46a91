#pragma once
// Test-only helpers: clips on disk (a stand-in video file and one haptic
// track per condition) in a fresh temporary directory.

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/haptic_track.h"

namespace hapcine::study::testing {

// Removes every directory made by MakeTempDir when the test program exits.
struct TempDirRegistry {
  std::vector<std::string> dirs;
  ~TempDirRegistry() {
    std::error_code ec;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
  }
};
inline TempDirRegistry g_temp_dirs;

inline std::string MakeTempDir(const std::string& tag) {
  std::string templ =
      (std::filesystem::temp_directory_path() / ("hapcine_study_" + tag + "_XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  if (!mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed");
  g_temp_dirs.dirs.push_back(buf.data());
  return buf.data();
}

// A 1 s track at 100 Hz; `kind` 0 = all zero (the "none" condition),
// otherwise a sinusoid whose frequency depends on kind; `offset_m` is added to
// every coordinate (to test the identical-track tolerance).
inline HapticTrack MakeTrack(const std::string& model, int kind, double offset_m = 0) {
  HapticTrack t;
  t.rate_hz = 100;
  t.model = model;
  t.source = "test.mp4";
  for (int i = 0; i <= 100; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    for (int a = 0; a < kNumActuators; ++a)
      for (int d = 0; d < 3; ++d)
        s.pos_m[a][d] = (kind == 0 ? 0.0 : 0.02 * std::sin(kind * s.time_s * 3 + a + d)) + offset_m;
    t.samples.push_back(s);
  }
  return t;
}

// Writes dir/<name>.mp4 (stand-in bytes) and dir/<name>.<cond>.haptic.csv for
// the four paper conditions. `cinematic_equals_none` makes the cinematic track
// all zero like "none" (the paper's Vertigo). Returns the video path.
inline std::string MakeClip(const std::string& dir, const std::string& name,
                            bool cinematic_equals_none = false, double cinematic_offset_m = 0) {
  const std::string video = dir + "/" + name + ".mp4";
  std::ofstream(video) << "not really a video: " << name << "\n";
  WriteHapticTrackFile(MakeTrack("cinematic", cinematic_equals_none ? 0 : 1, cinematic_offset_m),
                       dir + "/" + name + ".cinematic.haptic.csv");
  WriteHapticTrackFile(MakeTrack("semantic", 2), dir + "/" + name + ".semantic.haptic.csv");
  WriteHapticTrackFile(MakeTrack("none", 0), dir + "/" + name + ".none.haptic.csv");
  WriteHapticTrackFile(MakeTrack("random", 3), dir + "/" + name + ".random.haptic.csv");
  return video;
}

// The paper's seven sequences; Vertigo's cinematic track equals "none".
inline std::vector<std::string> MakePaperClips(const std::string& dir) {
  std::vector<std::string> clips;
  for (const char* n : {"crane", "dutch", "arcing", "traveling", "tilting", "zoomin", "vertigo"})
    clips.push_back(MakeClip(dir, n, std::string(n) == "vertigo"));
  return clips;
}

}  // namespace hapcine::study::testing
