#include "studio/media_tools.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include "core/child_process.h"
#include "core/error.h"
#include "core/text.h"

namespace hapcine::studio {
namespace {
namespace fs = std::filesystem;

bool OneOf(const std::string& value, const std::vector<std::string>& set) {
  for (const std::string& s : set) {
    if (value == s) return true;
  }
  return false;
}

bool BrowserPlays(const MediaProbe& p, const std::string& film) {
  const std::string ext = LowerExtension(film);
  const bool mp4 = (ext == ".mp4" || ext == ".m4v") && p.container.find("mp4") != std::string::npos;
  const bool webm = ext == ".webm" && p.container.find("webm") != std::string::npos;
  const bool video = OneOf(p.video_codec, {"h264", "vp8", "vp9", "av1"});
  const bool audio = p.audio_codec.empty() || OneOf(p.audio_codec, {"aac", "mp3", "opus", "vorbis", "flac"});
  return (mp4 || webm) && video && audio;
}

// Runs ffmpeg with `args`; throws Error(film, last line of its log) on failure.
void RunFfmpeg(const std::string& film, const std::vector<std::string>& args,
               const std::string& log) {
  std::vector<std::string> argv = {"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ChildResult r = RunChild(argv, log);
  if (!r.started) throw Error(film, "cannot run ffmpeg (is it installed? scripts/install_deps.sh)");
  if (!r.ok()) {
    const std::string line = LastNonEmptyLine(log);
    throw Error(film, "ffmpeg failed" + (line.empty() ? std::string() : ": " + line));
  }
}

// The last out_time_us= (microseconds) of an ffmpeg -progress file; -1 if none.
double LastProgressSeconds(const std::string& path) {
  std::ifstream in(path);
  double last = -1;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("out_time_us=", 0) == 0) {
      try {
        last = std::stod(line.substr(12)) / 1e6;
      } catch (...) {
      }
    }
  }
  return last;
}

}  // namespace

MediaProbe ProbeMedia(const std::string& film) {
  MediaProbe p;
  AVFormatContext* fmt = nullptr;
  // A file libavformat cannot read is an answer here, not a message.
  const int log_level = av_log_get_level();
  av_log_set_level(AV_LOG_FATAL);
  const int opened = avformat_open_input(&fmt, film.c_str(), nullptr, nullptr);
  av_log_set_level(log_level);
  if (opened != 0) return p;
  if (avformat_find_stream_info(fmt, nullptr) >= 0) {
    p.opened = true;
    p.container = fmt->iformat && fmt->iformat->name ? fmt->iformat->name : "";
    if (fmt->duration > 0) p.duration_s = fmt->duration / static_cast<double>(AV_TIME_BASE);
    const int v = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    const int a = av_find_best_stream(fmt, AVMEDIA_TYPE_AUDIO, -1, -1, nullptr, 0);
    if (v >= 0) p.video_codec = avcodec_get_name(fmt->streams[v]->codecpar->codec_id);
    if (a >= 0) p.audio_codec = avcodec_get_name(fmt->streams[a]->codecpar->codec_id);
    p.browser_playable = BrowserPlays(p, film);
  }
  avformat_close_input(&fmt);
  return p;
}

void MakeProxy(const std::string& film, double duration_s, const std::string& output,
               const std::function<void(double)>& progress) {
  const std::string temp = output + ".part.mp4";
  const std::string progress_file = output + ".progress";
  std::atomic<bool> finished{false};
  std::thread watcher([&] {
    while (!finished) {
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
      const double done_s = LastProgressSeconds(progress_file);
      if (progress && done_s >= 0 && duration_s > 0) progress(std::min(0.99, done_s / duration_s));
    }
  });
  try {
    RunFfmpeg(film,
              {"-i", film, "-map", "0:v:0", "-map", "0:a:0?", "-c:v", "libx264", "-preset", "veryfast",
               "-crf", "23", "-pix_fmt", "yuv420p", "-c:a", "aac", "-b:a", "160k", "-movflags",
               "+faststart", "-progress", progress_file, temp},
              output + ".log");
  } catch (...) {
    finished = true;
    watcher.join();
    std::remove(temp.c_str());
    throw;
  }
  finished = true;
  watcher.join();
  std::error_code ec;
  fs::rename(temp, output, ec);
  if (ec) throw Error(output, "cannot rename the proxy into place: " + ec.message());
  fs::remove(progress_file, ec);
}

void MakeThumbnail(const std::string& film, double time_s, int width, const std::string& output) {
  const std::string temp = output + ".part.jpg";
  std::error_code ec;
  // Past the video's end (a camera path longer than the film) ffmpeg writes
  // nothing: then the first frame.
  for (const double t : {std::max(0.0, time_s), 0.0}) {
    char at[32];
    std::snprintf(at, sizeof at, "%.3f", t);
    try {
      RunFfmpeg(film,
                {"-ss", at, "-i", film, "-frames:v", "1", "-vf",
                 "scale=" + std::to_string(width) + ":-2", "-q:v", "4", temp},
                output + ".log");
    } catch (...) {
      std::remove(temp.c_str());
      throw;
    }
    if (fs::exists(temp, ec)) break;
  }
  if (!fs::exists(temp, ec)) throw Error(film, "ffmpeg wrote no frame");
  fs::rename(temp, output, ec);
  if (ec) throw Error(output, "cannot rename the thumbnail into place: " + ec.message());
}

}  // namespace hapcine::studio
