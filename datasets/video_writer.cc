#include "datasets/video_writer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <cmath>

#include "core/output_files.h"
#include "core/error.h"
#include "extract/av_error.h"

namespace hapcine {
namespace {

// Exact rationals for the broadcast rates, so 23.976 is 24000/1001.
AVRational FpsRational(double fps) {
  for (int base : {24, 30, 60, 120}) {
    if (std::abs(fps - base * 1000.0 / 1001.0) < 1e-3) return AVRational{base * 1000, 1001};
  }
  return av_d2q(fps, 1000000);
}

}  // namespace

VideoWriter::~VideoWriter() { Abort(); }

void VideoWriter::Abort() noexcept {
  if (sws_) sws_freeContext(sws_);
  sws_ = nullptr;
  if (frame_) av_frame_free(&frame_);
  if (packet_) av_packet_free(&packet_);
  if (codec_) avcodec_free_context(&codec_);
  if (format_) {
    if (format_->pb) avio_closep(&format_->pb);
    avformat_free_context(format_);
    format_ = nullptr;
  }
  output_.Discard();  // no-op once committed
  header_written_ = false;
}

void VideoWriter::Open(const std::string& path, int width, int height, double fps,
                       const VideoWriterOptions& options) {
  if (format_) throw Error(path, "VideoWriter already open");
  if (width <= 0 || height <= 0 || width % 2 || height % 2) {
    throw Error(path, "video size must be positive and even, got " + std::to_string(width) +
                          "x" + std::to_string(height));
  }
  if (!(fps > 0 && std::isfinite(fps))) throw Error(path, "fps must be positive");
  if (options.crf < 0 || options.crf > 51) throw Error(path, "crf must be in [0, 51]");
  // libx264 prints its settings and statistics at INFO level; keep the
  // terminal for our own progress unless the user asked FFmpeg for more.
  if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_WARNING);
  path_ = path;
  if (options.atomic) output_ = TempOutput(path);
  const std::string temp_path = options.atomic ? output_.write_path() : path;
  width_ = width;
  height_ = height;
  frames_ = 0;
  try {
    // The temporary name has no .mp4 suffix, so name the muxer explicitly.
    int rc = avformat_alloc_output_context2(&format_, nullptr, "mp4", temp_path.c_str());
    if (rc < 0 || !format_) throw Error(path, "cannot create MP4 muxer: " + AvErrorText(rc));
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) throw Error(path, "FFmpeg has no libx264 encoder");
    stream_ = avformat_new_stream(format_, nullptr);
    codec_ = avcodec_alloc_context3(codec);
    if (!stream_ || !codec_) throw Error(path, "out of memory");
    const AVRational rate = FpsRational(fps);
    codec_->width = width;
    codec_->height = height;
    codec_->pix_fmt = AV_PIX_FMT_YUV420P;
    codec_->time_base = av_inv_q(rate);
    codec_->framerate = rate;
    codec_->gop_size = options.gop;
    codec_->thread_count = options.threads;
    codec_->colorspace = AVCOL_SPC_SMPTE170M;
    codec_->color_primaries = AVCOL_PRI_SMPTE170M;
    codec_->color_trc = AVCOL_TRC_SMPTE170M;
    codec_->color_range = AVCOL_RANGE_MPEG;
    if (format_->oformat->flags & AVFMT_GLOBALHEADER) {
      codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    }
    av_opt_set(codec_->priv_data, "preset", options.preset.c_str(), 0);
    av_opt_set(codec_->priv_data, "crf", std::to_string(options.crf).c_str(), 0);
    rc = avcodec_open2(codec_, codec, nullptr);
    if (rc < 0) throw Error(path, "cannot open libx264 (preset '" + options.preset + "'): " + AvErrorText(rc));
    rc = avcodec_parameters_from_context(stream_->codecpar, codec_);
    if (rc < 0) throw Error(path, "codec parameters: " + AvErrorText(rc));
    stream_->time_base = codec_->time_base;
    stream_->avg_frame_rate = rate;
    stream_->r_frame_rate = rate;
    rc = avio_open(&format_->pb, temp_path.c_str(), AVIO_FLAG_WRITE);
    if (rc < 0) throw Error(path, "cannot open for writing: " + AvErrorText(rc));
    rc = avformat_write_header(format_, nullptr);
    if (rc < 0) throw Error(path, "cannot write MP4 header: " + AvErrorText(rc));
    header_written_ = true;
    frame_ = av_frame_alloc();
    packet_ = av_packet_alloc();
    if (!frame_ || !packet_) throw Error(path, "out of memory");
    frame_->format = AV_PIX_FMT_YUV420P;
    frame_->width = width;
    frame_->height = height;
    frame_->colorspace = AVCOL_SPC_SMPTE170M;
    frame_->color_range = AVCOL_RANGE_MPEG;
    rc = av_frame_get_buffer(frame_, 0);
    if (rc < 0) throw Error(path, "frame buffer: " + AvErrorText(rc));
    sws_ = sws_getContext(width, height, AV_PIX_FMT_BGR24, width, height, AV_PIX_FMT_YUV420P,
                          SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr,
                          nullptr);
    if (!sws_) throw Error(path, "cannot create colour converter");
  } catch (...) {
    Abort();
    throw;
  }
}

void VideoWriter::Write(const cv::Mat& bgr) {
  if (!format_) throw Error(path_, "VideoWriter is not open");
  try {
    if (bgr.type() != CV_8UC3 || bgr.cols != width_ || bgr.rows != height_) {
      throw Error(path_, "frame must be CV_8UC3 " + std::to_string(width_) + "x" +
                             std::to_string(height_));
    }
    const int rc = av_frame_make_writable(frame_);
    if (rc < 0) throw Error(path_, "frame not writable: " + AvErrorText(rc));
    const uint8_t* src[1] = {bgr.data};
    const int stride[1] = {static_cast<int>(bgr.step[0])};
    sws_scale(sws_, src, stride, 0, height_, frame_->data, frame_->linesize);
    frame_->pts = frames_;
    Encode(frame_);
    ++frames_;
  } catch (...) {
    Abort();
    throw;
  }
}

void VideoWriter::Encode(AVFrame* frame) {
  int rc = avcodec_send_frame(codec_, frame);
  if (rc < 0) throw Error(path_, "encoder rejected a frame: " + AvErrorText(rc));
  for (;;) {
    rc = avcodec_receive_packet(codec_, packet_);
    if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
    if (rc < 0) throw Error(path_, "encoding failed: " + AvErrorText(rc));
    av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    rc = av_interleaved_write_frame(format_, packet_);  // takes the packet's data
    if (rc < 0) throw Error(path_, "write failed (disk full?): " + AvErrorText(rc));
  }
}

void VideoWriter::Close() {
  if (!format_) throw Error(path_, "VideoWriter is not open");
  try {
    if (frames_ == 0) throw Error(path_, "no frames written");
    Encode(nullptr);
    int rc = av_write_trailer(format_);
    if (rc < 0) throw Error(path_, "cannot finish MP4: " + AvErrorText(rc));
    rc = avio_closep(&format_->pb);
    if (rc < 0) throw Error(path_, "cannot close file: " + AvErrorText(rc));
  } catch (...) {
    Abort();
    throw;
  }
  // Release everything but keep the temporary file, then rename it.
  avformat_free_context(format_);
  format_ = nullptr;
  output_.Commit();  // no-op unless atomic; if this throws, the destructor releases the rest
  Abort();
}

}  // namespace hapcine
