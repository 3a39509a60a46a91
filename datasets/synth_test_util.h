#pragma once
// Test helper (header-only, used by the datasets tests): decodes a video with
// libavformat/libavcodec into BGR frames and their presentation times, the
// way the project's readers see it.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <string>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace hapcine::testing {

struct DecodedVideo {
  std::vector<cv::Mat> frames;  // BGR, CV_8UC3
  std::vector<double> times_s;  // best-effort pts * stream time base
  int codec_id = 0;
  int pix_fmt = -1;
  int colorspace = -1;
};

inline DecodedVideo DecodeVideo(const std::string& path) {
  DecodedVideo out;
  AVFormatContext* fmt = nullptr;
  if (avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) != 0) {
    ADD_FAILURE() << "cannot open " << path;
    return out;
  }
  avformat_find_stream_info(fmt, nullptr);
  const int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (si < 0) {
    ADD_FAILURE() << "no video stream in " << path;
    avformat_close_input(&fmt);
    return out;
  }
  AVStream* st = fmt->streams[si];
  out.codec_id = st->codecpar->codec_id;
  out.pix_fmt = st->codecpar->format;
  const AVCodec* dec = avcodec_find_decoder(st->codecpar->codec_id);
  AVCodecContext* ctx = avcodec_alloc_context3(dec);
  avcodec_parameters_to_context(ctx, st->codecpar);
  avcodec_open2(ctx, dec, nullptr);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  SwsContext* sws = nullptr;
  auto drain = [&]() {
    while (avcodec_receive_frame(ctx, frame) == 0) {
      out.colorspace = frame->colorspace;
      sws = sws_getCachedContext(sws, frame->width, frame->height,
                                 static_cast<AVPixelFormat>(frame->format), frame->width,
                                 frame->height, AV_PIX_FMT_BGR24, SWS_BICUBIC, nullptr, nullptr,
                                 nullptr);
      cv::Mat bgr(frame->height, frame->width, CV_8UC3);
      uint8_t* dst[1] = {bgr.data};
      const int dst_stride[1] = {static_cast<int>(bgr.step[0])};
      sws_scale(sws, frame->data, frame->linesize, 0, frame->height, dst, dst_stride);
      out.frames.push_back(bgr);
      out.times_s.push_back(frame->best_effort_timestamp * av_q2d(st->time_base));
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == si) {
      avcodec_send_packet(ctx, pkt);
      drain();
    }
    av_packet_unref(pkt);
  }
  avcodec_send_packet(ctx, nullptr);
  drain();
  sws_freeContext(sws);
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&ctx);
  avformat_close_input(&fmt);
  return out;
}

}  // namespace hapcine::testing
