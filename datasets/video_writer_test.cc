#include "datasets/video_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include "core/error.h"
#include "datasets/synth_test_util.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("hapcine_vw_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

cv::Mat Pattern(int w, int h, int k) {
  cv::Mat m(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      m.at<cv::Vec3b>(y, x) = cv::Vec3b((x * 3 + k * 5) % 256, (y * 4) % 256, 128);
    }
  }
  cv::GaussianBlur(m, m, cv::Size(5, 5), 1.5);
  return m;
}

TEST(VideoWriter, RoundTripFramesAndTimestamps) {
  const fs::path dir = TempDir("rt");
  const std::string path = (dir / "clip.mp4").string();
  VideoWriter w;
  w.Open(path, 160, 90, 24);
  EXPECT_FALSE(fs::exists(path));  // only the temporary exists while writing
  for (int k = 0; k < 10; ++k) w.Write(Pattern(160, 90, k));
  w.Close();
  ASSERT_TRUE(fs::exists(path));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  const testing::DecodedVideo d = testing::DecodeVideo(path);
  EXPECT_EQ(d.codec_id, AV_CODEC_ID_H264);
  EXPECT_EQ(d.pix_fmt, AV_PIX_FMT_YUV420P);
  ASSERT_EQ(d.frames.size(), 10u);
  EXPECT_EQ(d.frames[0].cols, 160);
  EXPECT_EQ(d.frames[0].rows, 90);
  ASSERT_EQ(d.times_s.size(), 10u);
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(d.times_s[k], k / 24.0, 1e-6) << k;
  fs::remove_all(dir);
}

TEST(VideoWriter, NtscRateIsExact) {
  const fs::path dir = TempDir("ntsc");
  const std::string path = (dir / "clip.mp4").string();
  VideoWriter w;
  w.Open(path, 64, 48, 24000.0 / 1001.0);
  for (int k = 0; k < 5; ++k) w.Write(Pattern(64, 48, k));
  w.Close();
  const testing::DecodedVideo d = testing::DecodeVideo(path);
  ASSERT_EQ(d.times_s.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(d.times_s[k], k * 1001.0 / 24000.0, 1e-6);
  fs::remove_all(dir);
}

TEST(VideoWriter, PixelsSurviveEncoding) {
  const fs::path dir = TempDir("px");
  const std::string path = (dir / "clip.mp4").string();
  const cv::Mat img = Pattern(128, 96, 3);
  {
    VideoWriter w;
    w.Open(path, 128, 96, 24);
    w.Write(img);
    w.Write(img);
    w.Close();
  }
  cv::Mat back;
  // Decode the first frame to BGR through the same library family as readers.
  AVFormatContext* fmt = nullptr;
  ASSERT_EQ(avformat_open_input(&fmt, path.c_str(), nullptr, nullptr), 0);
  avformat_find_stream_info(fmt, nullptr);
  AVStream* st = fmt->streams[0];
  const AVCodec* dec = avcodec_find_decoder(st->codecpar->codec_id);
  AVCodecContext* ctx = avcodec_alloc_context3(dec);
  avcodec_parameters_to_context(ctx, st->codecpar);
  avcodec_open2(ctx, dec, nullptr);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  bool got = false;
  while (!got && av_read_frame(fmt, pkt) >= 0) {
    avcodec_send_packet(ctx, pkt);
    av_packet_unref(pkt);
    got = avcodec_receive_frame(ctx, frame) == 0;
  }
  if (!got) {
    avcodec_send_packet(ctx, nullptr);
    got = avcodec_receive_frame(ctx, frame) == 0;
  }
  ASSERT_TRUE(got);
  // Compare luma with BT.601 limited-range luma of the input.
  double err = 0;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 128; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      const double luma = 16 + (65.481 * p[2] + 128.553 * p[1] + 24.966 * p[0]) / 255.0;
      err += std::abs(frame->data[0][y * frame->linesize[0] + x] - luma);
    }
  }
  EXPECT_LT(err / (128 * 96), 1.5);
  EXPECT_EQ(frame->colorspace, AVCOL_SPC_SMPTE170M);
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&ctx);
  avformat_close_input(&fmt);
  fs::remove_all(dir);
}

TEST(VideoWriter, BadInputLeavesNothingBehind) {
  const fs::path dir = TempDir("bad");
  VideoWriter w;
  EXPECT_THROW(w.Open((dir / "odd.mp4").string(), 161, 90, 24), Error);
  EXPECT_THROW(w.Open((dir / "nodir" / "x.mp4").string(), 160, 90, 24), Error);
  EXPECT_THROW(w.Open((dir / "fps.mp4").string(), 160, 90, 0), Error);
  {
    VideoWriter aborted;
    aborted.Open((dir / "aborted.mp4").string(), 160, 90, 24);
    aborted.Write(Pattern(160, 90, 0));
    EXPECT_THROW(aborted.Write(Pattern(80, 90, 0)), Error);  // wrong size aborts the file
    EXPECT_FALSE(aborted.is_open());
  }
  {
    VideoWriter dropped;  // destroyed without Close()
    dropped.Open((dir / "dropped.mp4").string(), 160, 90, 24);
    dropped.Write(Pattern(160, 90, 0));
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hapcine
