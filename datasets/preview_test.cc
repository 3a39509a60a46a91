#include "datasets/preview.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "core/camera_path.h"
#include "core/error.h"
#include "core/haptic_track.h"
#include "extract/frame_source.h"

extern "C" {
#include <libavformat/avformat.h>
}

namespace hapcine {
namespace {
namespace fs = std::filesystem;

bool HaveFfmpeg() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

// What a rendered file holds, from its packets (the edit list applied:
// packets the demuxer marks discardable, AAC's priming, are not counted).
struct Probed {
  int video_packets = 0;
  double video_first_s = 1e9, video_end_s = 0;
  double audio_first_s = 1e9, audio_end_s = 0;
  std::string audio_codec;  // empty: no audio stream
};

Probed Probe(const std::string& path) {
  Probed p;
  AVFormatContext* ctx = nullptr;
  if (avformat_open_input(&ctx, path.c_str(), nullptr, nullptr) < 0) return p;
  avformat_find_stream_info(ctx, nullptr);
  for (unsigned i = 0; i < ctx->nb_streams; ++i)
    if (ctx->streams[i]->codecpar->codec_type == AVMEDIA_TYPE_AUDIO)
      p.audio_codec = avcodec_get_name(ctx->streams[i]->codecpar->codec_id);
  AVPacket* pkt = av_packet_alloc();
  while (av_read_frame(ctx, pkt) >= 0) {
    const AVStream* st = ctx->streams[pkt->stream_index];
    const double tb = av_q2d(st->time_base);
    const double t0 = pkt->pts * tb, t1 = (pkt->pts + pkt->duration) * tb;
    if (!(pkt->flags & AV_PKT_FLAG_DISCARD) && pkt->pts != AV_NOPTS_VALUE) {
      const bool video = st->codecpar->codec_type == AVMEDIA_TYPE_VIDEO;
      p.video_packets += video;
      double& first = video ? p.video_first_s : p.audio_first_s;
      double& end = video ? p.video_end_s : p.audio_end_s;
      first = std::min(first, t0);
      end = std::max(end, t1);
    }
    av_packet_unref(pkt);
  }
  av_packet_free(&pkt);
  avformat_close_input(&ctx);
  return p;
}

// A 2 s clip at 20 fps whose brightness counts the frames (frame N has luma
// 16 + 6 N), with a 440 Hz tone in `audio_codec` ("" for none).
fs::path CountingClip(const fs::path& dir, const std::string& name, const std::string& audio_codec) {
  const fs::path video = dir / name;
  std::string cmd = "ffmpeg -loglevel error -y -f lavfi -i \"nullsrc=s=160x120:r=20:d=2,"
                    "geq=lum='16+6*N':cb=128:cr=128\" ";
  if (!audio_codec.empty())
    cmd += "-f lavfi -i sine=frequency=440:duration=2:sample_rate=44100 -c:a " + audio_codec + " ";
  cmd += "-c:v libx264 -pix_fmt yuv420p -shortest " + video.string();
  if (std::system(cmd.c_str()) != 0) return {};
  return video;
}

// A track that holds still (the inset is drawn; its content does not matter here).
void WriteStillTrack(const fs::path& file) {
  HapticTrack t;
  t.rate_hz = 10;
  t.model = "cinematic";
  t.source = "clip.mp4";
  for (int i = 0; i <= 20; ++i) {
    HapticSample s;
    s.time_s = i / 10.0;
    t.samples.push_back(s);
  }
  WriteHapticTrackFile(t, file.string());
}

cv::Mat FirstFrame(const std::string& path) {
  FrameSourceOptions fo;
  fo.max_working_side = 0;
  auto src = OpenFrameSource(path, fo);
  Frame f;
  EXPECT_TRUE(src->Next(&f));
  return f.bgr;
}

TEST(Preview, RendersEveryFrameWithTheInsetAndWritesAtomically) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_test_tmp";
  fs::create_directories(d);
  const fs::path video = d / "clip.mp4";
  const std::string cmd =
      "ffmpeg -loglevel error -y -f lavfi -i color=c=black:duration=1:size=160x120:rate=20 "
      "-pix_fmt yuv420p " +
      video.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  HapticTrack t;
  t.rate_hz = 20;
  t.model = "cinematic";
  t.source = "clip.mp4";
  for (int i = 0; i <= 20; ++i) {
    HapticSample s;
    s.time_s = i / 20.0;
    s.pos_m[0] = Eigen::Vector3d(0.04 * i / 20.0, 0.03, 0);
    t.samples.push_back(s);
  }
  WriteHapticTrackFile(t, (d / "clip.haptic.csv").string());
  PreviewOptions o;
  o.video = video.string();
  o.output = (d / "out.mp4").string();
  fs::remove(o.output);
  EXPECT_EQ(RenderPreview(o), 20);
  ASSERT_TRUE(fs::exists(o.output));
  // The inset is drawn: the black clip is no longer black bottom-right.
  FrameSourceOptions fo;
  fo.max_working_side = 0;
  auto src = OpenFrameSource(o.output, fo);
  Frame f;
  ASSERT_TRUE(src->Next(&f));
  const cv::Rect inset(f.bgr.cols / 2, f.bgr.rows / 2, f.bgr.cols / 2, f.bgr.rows / 2);
  EXPECT_GT(cv::mean(f.bgr(inset))[0] + cv::mean(f.bgr(inset))[1], 5.0);
  EXPECT_LT(cv::mean(f.bgr(cv::Rect(f.bgr.cols - 20, 0, 20, 20)))[0], 5.0);  // burn-in: top-left
  // With a simulated response, its ring (light blue) is drawn too; the
  // callback gets the track that was read.
  auto count_ring_pixels = [](const cv::Mat& bgr) {
    int n = 0;
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x) {
        const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
        n += p[0] > 180 && p[1] > 130 && p[1] < 230 && p[2] < 110;
      }
    return n;
  };
  o.inset_fraction = 1;  // panels big enough to draw at 160x120
  fs::remove(o.output);
  ASSERT_EQ(RenderPreview(o), 20);
  auto src1 = OpenFrameSource(o.output, fo);
  ASSERT_TRUE(src1->Next(&f));
  EXPECT_EQ(count_ring_pixels(f.bgr), 0);
  size_t rows_seen = 0;
  o.simulate = [&rows_seen](const HapticTrack& targets) {
    rows_seen = targets.samples.size();
    HapticTrack r = targets;
    for (auto& s : r.samples) s.pos_m[2] = Eigen::Vector3d(-0.03, 0.02, 0.03);
    return r;
  };
  fs::remove(o.output);
  EXPECT_EQ(RenderPreview(o), 20);
  EXPECT_EQ(rows_seen, t.samples.size());
  auto src2 = OpenFrameSource(o.output, fo);
  ASSERT_TRUE(src2->Next(&f));
  EXPECT_GT(count_ring_pixels(f.bgr), 5);
  o.simulate = nullptr;
  // Bad input: no output left behind.
  o.video = (d / "missing.mp4").string();
  o.track = (d / "clip.haptic.csv").string();
  o.output = (d / "bad.mp4").string();
  EXPECT_THROW(RenderPreview(o), Error);
  EXPECT_FALSE(fs::exists(o.output));
}

TEST(Preview, KeepsTheFilmsSoundCopiedOrAsAac) {
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_audio_test_tmp";
  fs::create_directories(d);
  WriteStillTrack(d / "track.haptic.csv");
  // AAC in MP4 is copied; PCM in Matroska, which MP4 does not hold, is encoded as AAC.
  for (const auto& [name, codec] : {std::pair<std::string, std::string>{"aac.mp4", "aac"},
                                    {"pcm.mkv", "pcm_s16le"}}) {
    const fs::path clip = CountingClip(d, name, codec);
    ASSERT_FALSE(clip.empty()) << name;
    PreviewOptions o;
    o.video = clip.string();
    o.track = (d / "track.haptic.csv").string();
    o.output = (d / (name + ".preview.mp4")).string();
    fs::remove(o.output);
    EXPECT_EQ(RenderPreview(o), 40) << name;
    const Probed p = Probe(o.output);
    EXPECT_EQ(p.audio_codec, "aac") << name;
    EXPECT_EQ(p.video_packets, 40) << name;
    // The sound lasts as long as the pictures, within a frame (0.05 s).
    EXPECT_NEAR(p.audio_end_s - p.audio_first_s, 2.0, 0.05) << name;
    EXPECT_NEAR(p.audio_first_s, 0, 0.05) << name;
    // --no-audio: pictures only.
    o.audio = false;
    fs::remove(o.output);
    EXPECT_EQ(RenderPreview(o), 40) << name;
    EXPECT_EQ(Probe(o.output).audio_codec, "") << name;
  }
  // Only temporaries of ours could be left: none are.
  for (const auto& e : fs::directory_iterator(d))
    EXPECT_EQ(e.path().string().find("hapcine-tmp"), std::string::npos) << e.path();
}

TEST(Preview, RangeRendersThoseFramesWithTheirSound) {
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_range_test_tmp";
  fs::create_directories(d);
  WriteStillTrack(d / "track.haptic.csv");
  for (const std::string codec : {"aac", ""}) {
    const fs::path clip = CountingClip(d, codec.empty() ? "silent.mp4" : "aac.mp4", codec);
    ASSERT_FALSE(clip.empty());
    PreviewOptions o;
    o.video = clip.string();
    o.track = (d / "track.haptic.csv").string();
    o.output = (d / "range.mp4").string();
    o.burn_in = false;
    // Seconds and timecode: 0.5 s is frame 10 at 20 fps.
    o.from = "00:00:00:10";
    o.to = "1.5";
    fs::remove(o.output);
    EXPECT_EQ(RenderPreview(o), 20) << codec;
    const Probed p = Probe(o.output);
    EXPECT_EQ(p.video_packets, 20);
    EXPECT_NEAR(p.video_first_s, 0, 1e-3);
    EXPECT_NEAR(p.video_end_s - p.video_first_s, 1.0, 0.05);
    if (!codec.empty()) {
      EXPECT_NEAR(p.audio_first_s, 0, 0.05);
      EXPECT_NEAR(p.audio_end_s - p.audio_first_s, 1.0, 0.05);
    } else {
      EXPECT_EQ(p.audio_codec, "");
    }
    // The first picture is the film's frame 10 (luma 16 + 60, 70 in full
    // range; frames 9 and 11 are 7 apart), left of the inset.
    const cv::Mat first = FirstFrame(o.output);
    cv::Mat gray;
    cv::cvtColor(first(cv::Rect(4, 50, 60, 30)), gray, cv::COLOR_BGR2GRAY);
    EXPECT_NEAR(cv::mean(gray)[0], 60 * 255.0 / 219, 3) << codec;
  }
}

TEST(Preview, BadRangeIsAUsageErrorAndWritesNothing) {
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_bad_range_test_tmp";
  fs::create_directories(d);
  WriteStillTrack(d / "track.haptic.csv");
  const fs::path clip = CountingClip(d, "clip.mp4", "aac");
  ASSERT_FALSE(clip.empty());
  PreviewOptions o;
  o.video = clip.string();
  o.track = (d / "track.haptic.csv").string();
  o.output = (d / "out.mp4").string();
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"1.5", "0.5"}, {"1", "1"}, {"3", ""}, {"00:00:00:20", "00:00:00:25"}, {"x", ""},
           {"1.98", "1.99"}}) {
    o.from = from;
    o.to = to;
    fs::remove(o.output);
    EXPECT_THROW(RenderPreview(o), UsageError) << from << " " << to;
    EXPECT_FALSE(fs::exists(o.output)) << from << " " << to;
  }
  for (const auto& e : fs::directory_iterator(d))
    EXPECT_EQ(e.path().string().find("hapcine-tmp"), std::string::npos) << e.path();
}

TEST(Preview, BurnsInTheTimecodeShotCameraModelAndEffect) {
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "preview_burn_in_test_tmp";
  fs::create_directories(d);
  const fs::path clip = CountingClip(d, "clip.mp4", "");
  ASSERT_FALSE(clip.empty());
  WriteStillTrack(d / "clip.haptic.csv");
  // The camera path beside the film is found without --camera.
  CameraPath path;
  for (int i = 0; i < 40; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 20.0;
    f.fov_deg = 60;
    f.shot = 0;
    f.model = "static";
    path.frames.push_back(f);
  }
  WriteCameraPathFile(path, (d / "clip.camera.csv").string());
  PreviewOptions o;
  o.video = clip.string();
  o.output = (d / "with.mp4").string();
  fs::remove(o.output);
  ASSERT_EQ(RenderPreview(o), 40);
  const cv::Mat with = FirstFrame(o.output);
  o.burn_in = false;
  o.output = (d / "without.mp4").string();
  fs::remove(o.output);
  ASSERT_EQ(RenderPreview(o), 40);
  const cv::Mat without = FirstFrame(o.output);
  // Three lines top-left change the picture there, and only there.
  cv::Mat diff;
  cv::absdiff(with, without, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(diff(cv::Rect(0, 0, 80, 40)) > 60), 50);
  EXPECT_EQ(cv::countNonZero(diff(cv::Rect(0, 60, 80, 60)) > 60), 0);
}

}  // namespace
}  // namespace hapcine
