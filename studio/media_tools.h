#pragma once
// What the studio needs of a film besides its camera path: whether a browser
// can play it as it is, an H.264 proxy when it cannot, and a JPEG per shot
// for the timeline. The proxy and thumbnails are made by the `ffmpeg`
// program (Debian's ffmpeg, in scripts/install_deps.sh) as a child process,
// into a cache folder beside the film's outputs.

#include <functional>
#include <string>

namespace hapcine::studio {

struct MediaProbe {
  bool opened = false;        // libavformat read the file
  std::string container;      // libavformat's name, e.g. "mov,mp4,m4a,3gp,3g2,mj2"
  std::string video_codec;    // e.g. "h264"
  std::string audio_codec;    // "" without audio
  double duration_s = 0;      // 0 when unknown
  // A browser's <video> plays it: H.264, VP8, VP9 or AV1 in an .mp4/.m4v or
  // .webm file (audio AAC, MP3, Opus, Vorbis or FLAC, or none). A file
  // libavformat cannot read is served as it is (nothing better to offer).
  bool browser_playable = true;
};

// Never throws.
MediaProbe ProbeMedia(const std::string& film);

// Re-encodes `film` as H.264/AAC MP4 into `output` (written under a
// temporary name, renamed when complete). `progress` gets [0, 1] from
// ffmpeg's -progress output. Throws hapcine::Error(film, reason) on failure.
void MakeProxy(const std::string& film, double duration_s, const std::string& output,
               const std::function<void(double)>& progress);

// One JPEG, `width` pixels wide, of the frame at `time_s` (written
// atomically). Throws hapcine::Error(film, reason) on failure.
void MakeThumbnail(const std::string& film, double time_s, int width, const std::string& output);

}  // namespace hapcine::studio
