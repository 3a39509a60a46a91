#pragma once
// The platform track file (*.platform.csv, docs/formats.md "Platform track"):
// the pose of a motion platform per sample at a fixed rate and, for a
// Stewart platform, its six leg lengths.
//
//   # type=platform
//   # rate_hz=100
//   # model=cinematic
//   # source=clip.camera.csv
//   # platform=<name>
//   # dofs=heave pitch roll   (+ other key=value lines)
//   time_s,x_m,y_m,z_m,pitch_deg,yaw_deg,roll_deg[,leg1_m,...,leg6_m][,shot]
//
// Pose in the seat frame of the haptic track (platform_config.h): x = sway
// (+ right), y = heave (+ up), z = surge (+ backward), pitch about +X (+ front
// up), yaw about +Y (+ turning left), roll about +Z (+ right side up).

#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "platform/platform_config.h"
#include "platform/stewart.h"

namespace hapcine {

struct PlatformSample {
  double time_s = 0;
  PlatformPose pose = PlatformPose::Zero();  // metres, radians
  std::optional<LegLengths> legs;            // Stewart platforms only
  std::optional<int> shot;
};

struct PlatformTrack {
  double rate_hz = 100;
  std::string model = "none";
  std::string source;
  std::string platform;  // the config's name
  std::string dofs;      // enabled DOFs, space separated
  std::map<std::string, std::string> metadata;  // other "# key=value" lines
  std::vector<PlatformSample> samples;
  double duration_s() const {
    return samples.empty() ? 0 : samples.back().time_s - samples.front().time_s;
  }
};

// Throws Error("platform track", ...) on non-finite values or time not
// increasing; writes legs when every sample has them.
void WritePlatformTrack(const PlatformTrack& track, std::ostream& out);
// Throws Error("<source>:<line>", reason) on a wrong header, missing
// metadata (type=platform, rate_hz, model, source), non-finite values, time
// not increasing, |position| > 1 m or |angle| > 90 deg.
PlatformTrack ReadPlatformTrack(std::istream& in, const std::string& source_name);
PlatformTrack ReadPlatformTrackFile(const std::string& path);
// Whether the file starts like a platform track (a "# type=platform" line
// among its metadata lines).
bool LooksLikePlatformTrackFile(const std::string& path);

}  // namespace hapcine
