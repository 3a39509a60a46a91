#pragma once
// The film's sound under a rendered preview: the video stream of a rendered
// MP4 and the film's audio stream (the one FFmpeg would choose) over
// [from_s, to_s) muxed into one MP4, the audio shifted so that from_s is 0.
// The audio is copied where MP4 holds its codec well (AAC, MP3, AC-3, E-AC-3,
// ALAC) and encoded as AAC otherwise (PCM, Vorbis, FLAC, ...): mono stays
// mono, more channels become stereo.
//
// Film times are the frame source's: relative to the video stream's start
// (extract/frame_source.h), so the sound stays in sync with the frames of a
// film whose streams start late or apart. A copied range starts with the
// first audio packet at or after from_s (an AAC packet lasts ~21 ms, under a
// frame); an encoded range is cut to the sample.

#include <string>

namespace hapcine {

struct AudioRange {
  double from_s = 0;
  double to_s = -1;  // < 0: to the end
};

// True when `film` has an audio stream that FFmpeg can open; false for a
// silent film (and for anything FFmpeg cannot read: the preview's own
// decoder reports that).
bool FilmHasAudio(const std::string& film);

// Writes `output_path` (a plain path: the caller makes it atomic) from the
// single video stream of `video_only`, copied, and the film's audio over
// `range`. Returns how the audio went in: "copy" or "aac". Throws
// Error(error_name, reason).
std::string MuxFilmAudio(const std::string& video_only, const std::string& film,
                         const AudioRange& range, const std::string& output_path,
                         const std::string& error_name);

}  // namespace hapcine
