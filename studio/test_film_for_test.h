#pragma once
// Test-only: a film folder for the studio's tests, made in milliseconds: a
// camera path of two shots (a tilt, then a crane shot; 7 s each at 30 fps)
// and a "film" whose bytes are a known pattern (Range tests check them;
// libavformat cannot read it, so it is served as it is).

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/camera_path.h"
#include "haptics/test_paths_for_test.h"

namespace hapcine::testing {

// Byte i of the test film.
inline char FilmByte(size_t i) { return static_cast<char>((i * 31 + i / 251) & 0xff); }

class StudioTestFilm {
 public:
  explicit StudioTestFilm(size_t film_bytes = 300000) {
    static std::atomic<int> counter{0};
    dir_ = std::filesystem::temp_directory_path() /
           ("hapcine_studio_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream film(this->film(), std::ios::binary);
    for (size_t i = 0; i < film_bytes; ++i) film.put(FilmByte(i));
    film.close();
    CameraPath path = MakeEffectPath({CameraEffect::kTilting});
    const CameraPath second = MakeEffectPath({CameraEffect::kCraneShot});
    const double shift = path.frames.back().time_s + 1.0 / 30;
    for (CameraFrame& f : path.frames) f.shot = 0;
    for (CameraFrame f : second.frames) {
      f.time_s += shift;
      f.frame += static_cast<int>(path.frames.size());
      f.shot = 1;
      path.frames.push_back(f);
    }
    path.metadata["width"] = "640";
    path.metadata["height"] = "360";
    WriteCameraPathFile(path, camera());
  }
  ~StudioTestFilm() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string dir() const { return dir_.string(); }
  std::string film() const { return (dir_ / "film.mp4").string(); }
  std::string camera() const { return (dir_ / "film.camera.csv").string(); }
  std::string edits() const { return (dir_ / "film.edits.json").string(); }

 private:
  std::filesystem::path dir_;
};

}  // namespace hapcine::testing
