// FrameSource over FFmpeg: demux (libavformat) -> decode (libavcodec, frame
// threads) -> scale straight to the working size in gray and BGR (libswscale,
// one pass each, no extra resize) -> rotate by the display matrix.
//
// Streaming: one AVPacket and one AVFrame are reused for the whole file, so
// memory does not grow with the video's length. Times come from the
// container (best_effort_timestamp), so variable frame rate comes out right.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <opencv2/core.hpp>
#include <queue>
#include <string>
#include <vector>

#include "core/error.h"
#include "extract/av_error.h"
#include "extract/half_gray.h"
#include "extract/video_sources.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/display.h>
#include <libavutil/pixdesc.h>
#include <libavutil/rational.h>
#include <libswscale/swscale.h>
}

namespace hapcine {
namespace {

// Clockwise rotation (0/90/180/270) that makes the frame display upright,
// the same reading as the ffmpeg CLI's autorotate.
int DisplayRotationDeg(const AVStream* stream) {
  const uint8_t* matrix = av_stream_get_side_data(stream, AV_PKT_DATA_DISPLAYMATRIX, nullptr);
  if (!matrix) return 0;
  const double ccw = av_display_rotation_get(reinterpret_cast<const int32_t*>(matrix));
  if (!std::isfinite(ccw)) return 0;
  double cw = -ccw;
  cw -= 360.0 * std::floor(cw / 360.0);  // [0, 360)
  const int quarter = static_cast<int>(std::lround(cw / 90.0)) % 4;
  return quarter * 90;
}

// The stream's sample aspect ratio (container, else codec: what the ffmpeg
// CLI's setsar/pasp/VUI give), reduced; 1:1 when undeclared or absurd
// (beyond 1:4..4:1 no camera writes it, and a broken header must not
// stretch the picture past what a decoder would show).
AVRational StreamSampleAspect(AVFormatContext* fmt, AVStream* stream) {
  AVRational sar = av_guess_sample_aspect_ratio(fmt, stream, nullptr);
  if (sar.num <= 0 || sar.den <= 0) return {1, 1};
  av_reduce(&sar.num, &sar.den, sar.num, sar.den, 1 << 16);
  const double r = av_q2d(sar);
  if (r < 0.25 || r > 4) return {1, 1};
  return sar;
}

// Stored width scaled to square pixels, rounded, at least 1.
int DisplayWidth(int stored_width, AVRational sar) {
  if (sar.num == sar.den) return stored_width;
  return std::max(1, static_cast<int>(std::lround(stored_width * av_q2d(sar))));
}

// Rows of a cv::Mat handed to swscale should start 16-byte aligned, or
// swscale falls back to slow paths (and says so on stderr).
bool RowsAligned(const cv::Mat& m) {
  return (reinterpret_cast<uintptr_t>(m.data) % 16 == 0) && (m.step % 16 == 0);
}

class FfmpegSource : public FrameSource {
 public:
  FfmpegSource(const std::string& path, const FrameSourceOptions& options) : options_(options) {
    info_.path = path;
    try {
      Open();
    } catch (...) {
      Close();
      throw;
    }
  }
  ~FfmpegSource() override { Close(); }

  const VideoInfo& info() const override { return info_; }
  std::vector<double> SkippedAtEnd() const override { return skipped_at_end_s_; }
  std::vector<std::string> Warnings() const override { return warnings_; }

  bool Next(Frame* out) override {
    if (finished_) return false;
    for (;;) {
      const int r = avcodec_receive_frame(dec_, frame_);
      if (r == 0) {
        Convert(out);
        av_frame_unref(frame_);
        ++decoded_;
        return true;
      }
      if (r == AVERROR_EOF) return Finish();
      if (r != AVERROR(EAGAIN)) {
        // A decoder error after draining started (truncated or corrupt tail):
        // keep what was decoded, stop cleanly.
        if (draining_) return Finish();
        ++bad_packets_;
        CheckBadPackets();
        continue;
      }
      if (draining_) return Finish();  // EAGAIN while draining: nothing left
      FeedOnePacket();
    }
  }

 private:
  void Open() {
    const std::string& path = info_.path;
    // FFmpeg's own messages ("moov atom not found") would add lines to the
    // one-line error this class throws with the same reason.
    if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_FATAL);
    int r = avformat_open_input(&fmt_, path.c_str(), nullptr, nullptr);
    if (r < 0) throw Error(path, "not a media file FFmpeg can read (" + AvErrorText(r) + ")");
    // The "tty" demuxer turns any .txt/.ans file into ANSI-art video.
    if (fmt_->iformat && std::strcmp(fmt_->iformat->name, "tty") == 0)
      throw Error(path, "not a media file (text)");
    r = avformat_find_stream_info(fmt_, nullptr);
    if (r < 0) throw Error(path, "cannot read stream information (" + AvErrorText(r) + ")");

    stream_index_ = PickVideoStream();
    AVStream* st = fmt_->streams[stream_index_];
    const AVCodecParameters* par = st->codecpar;
    info_.codec = avcodec_get_name(par->codec_id);
    const AVCodec* codec = avcodec_find_decoder(par->codec_id);
    if (!codec) {
      if (par->codec_id == AV_CODEC_ID_NONE && par->codec_tag != 0) {  // say which, at least
        char tag[AV_FOURCC_MAX_STRING_SIZE] = {0};
        av_fourcc_make_string(tag, par->codec_tag);
        throw Error(path, std::string("unsupported video codec: tag '") + tag +
                              "' is unknown to this FFmpeg");
      }
      throw Error(path,
                  "unsupported video codec '" + info_.codec + "' (no decoder in this FFmpeg)");
    }
    CheckSize(par->width, par->height);

    dec_ = avcodec_alloc_context3(codec);
    if (!dec_) throw Error(path, "out of memory (decoder context)");
    r = avcodec_parameters_to_context(dec_, par);
    if (r < 0) throw Error(path, "bad codec parameters (" + AvErrorText(r) + ")");
    dec_->pkt_timebase = st->time_base;
    dec_->thread_count = options_.decode_threads;  // 0 = automatic
    dec_->thread_type = FF_THREAD_FRAME | FF_THREAD_SLICE;
    if (options_.skip_loop_filter) dec_->skip_loop_filter = AVDISCARD_ALL;
    skipping_ = options_.skip_nonref_frames;
    if (skipping_) dec_->skip_frame = AVDISCARD_NONREF;
    r = avcodec_open2(dec_, codec, nullptr);
    if (r < 0) throw Error(path, "cannot open " + info_.codec + " decoder (" + AvErrorText(r) + ")");

    pkt_ = av_packet_alloc();
    frame_ = av_frame_alloc();
    if (!pkt_ || !frame_) throw Error(path, "out of memory (packet/frame)");

    time_base_s_ = av_q2d(st->time_base);
    if (st->start_time != AV_NOPTS_VALUE) start_pts_ = st->start_time;
    const AVRational rate = av_guess_frame_rate(fmt_, st, nullptr);
    info_.fps = (rate.num > 0 && rate.den > 0) ? av_q2d(rate) : 0;
    if (st->duration != AV_NOPTS_VALUE && st->duration > 0)
      info_.duration_s = st->duration * time_base_s_;
    else if (fmt_->duration != AV_NOPTS_VALUE && fmt_->duration > 0)
      info_.duration_s = static_cast<double>(fmt_->duration) / AV_TIME_BASE;
    if (st->nb_frames > 0)
      info_.frame_count = st->nb_frames;
    else if (info_.duration_s > 0 && info_.fps > 0)
      info_.frame_count = std::lround(info_.duration_s * info_.fps);
    info_.rotation_deg = DisplayRotationDeg(st);
    // Anamorphic pixels are resampled to square ones: the working images
    // are scaled to the display aspect by the same swscale pass that
    // shrinks them, so KLT's windows, the pinhole model and its single
    // focal length all see square pixels, at no extra cost.
    sar_ = StreamSampleAspect(fmt_, st);
    info_.sample_aspect_num = sar_.num;
    info_.sample_aspect_den = sar_.den;
    const int display_w = DisplayWidth(par->width, sar_);
    CheckSize(display_w, par->height);
    const bool swap = info_.rotation_deg == 90 || info_.rotation_deg == 270;
    info_.width = swap ? par->height : display_w;
    info_.height = swap ? display_w : par->height;
  }

  int PickVideoStream() {
    const std::string& path = info_.path;
    const int best = av_find_best_stream(fmt_, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    auto usable = [&](int i) {
      const AVStream* s = fmt_->streams[i];
      return s->codecpar->codec_type == AVMEDIA_TYPE_VIDEO &&
             !(s->disposition & AV_DISPOSITION_ATTACHED_PIC);
    };
    if (best >= 0 && usable(best)) return best;
    for (unsigned i = 0; i < fmt_->nb_streams; ++i)
      if (usable(static_cast<int>(i))) return static_cast<int>(i);
    bool has_audio = false;
    for (unsigned i = 0; i < fmt_->nb_streams; ++i)
      has_audio |= fmt_->streams[i]->codecpar->codec_type == AVMEDIA_TYPE_AUDIO;
    throw Error(path, has_audio ? "no video stream (audio only)" : "no video stream");
  }

  void CheckSize(int w, int h) const {
    if (w <= 0 || h <= 0) throw Error(info_.path, "video has no valid frame size");
    if (w > kMaxFrameSidePx || h > kMaxFrameSidePx)
      throw Error(info_.path, "absurd frame size " + std::to_string(w) + "x" + std::to_string(h) +
                                  " (limit " + std::to_string(kMaxFrameSidePx) + " px per side)");
  }

  void FeedOnePacket() {
    for (;;) {
      const int r = av_read_frame(fmt_, pkt_);
      if (r < 0) {  // end of file, or a read error on a truncated file
        avcodec_send_packet(dec_, nullptr);
        draining_ = true;
        return;
      }
      if (pkt_->stream_index != stream_index_) {
        av_packet_unref(pkt_);
        continue;
      }
      NoteVideoPacket();
      // Outside the edit list: decoded for reference, never shown.
      if (pkt_->flags & AV_PKT_FLAG_DISCARD) ++discarded_packets_;
      const int s = avcodec_send_packet(dec_, pkt_);
      av_packet_unref(pkt_);
      if (s < 0 && s != AVERROR(EAGAIN)) {  // corrupt packet: skip it
        ++bad_packets_;
        CheckBadPackets();
      }
      return;
    }
  }

  void CheckBadPackets() const {
    if (decoded_ == 0 && bad_packets_ > 200)
      throw Error(info_.path, "cannot decode any video frame (" + info_.codec + " data corrupt)");
  }

  bool Finish() {
    finished_ = true;
    if (decoded_ == 0) throw Error(info_.path, "no video frame could be decoded");
    CheckNotTruncated();
    // Frames skipped after the last decoded one (a non-reference frame shown
    // last: HEVC's low-delay B-frames) have no later frame to carry them.
    while (!unseen_pts_.empty() && start_pts_ != AV_NOPTS_VALUE) {
      const double t = (unseen_pts_.top() - start_pts_) * time_base_s_;
      unseen_pts_.pop();
      if (t > last_time_s_) skipped_at_end_s_.push_back(t);
    }
    CheckFramesDecoded();
    return false;
  }

  // The frames given out: decoded, or skipped on request and counted.
  long FramesGiven() const {
    if (!options_.skip_nonref_frames) return decoded_;
    return presented_ + static_cast<long>(skipped_at_end_s_.size());
  }

  // A file whose index is intact but whose data is not (spliced from two
  // files, overwritten) reads every packet the index lists and decodes only
  // some: the camera path would lose frames without a word. Against the
  // frame count the container declares (less the frames its edit list
  // leaves out), more than max(2 frames, 1 %) missing is an error; fewer,
  // a warning the caller reads (Warnings()).
  void CheckFramesDecoded() {
    int64_t listed = fmt_->streams[stream_index_]->nb_frames;
    if (listed <= 0) return;  // no frame count (Matroska): CheckNotTruncated's times
    if (SlotsHaveGaps()) listed = video_packets_;  // the empty slots hold no frame
    const long declared = static_cast<long>(listed) - discarded_packets_;
    long missing = declared - FramesGiven();
    // Skipping, a packet that failed to decode left its timestamp behind as
    // a skipped frame's: count the failures instead.
    if (options_.skip_nonref_frames) missing = std::max(missing, bad_packets_);
    if (missing <= 0) return;
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "%ld of the %ld frames declared could not be decoded (corrupt or spliced "
                  "video data)",
                  missing, declared);
    if (missing > std::max(2.0, 0.01 * static_cast<double>(declared)))
      throw Error(info_.path, buf);
    warnings_.push_back(buf);
  }

  // How far the demuxer got in the video stream (packets, and the end time of
  // the latest one from the stream start), to tell a truncated file from a
  // complete one when it ends.
  void NoteVideoPacket() {
    ++video_packets_;
    if (skipping_) {
      if (pkt_->pts != AV_NOPTS_VALUE) {
        unseen_pts_.push(pkt_->pts);
      } else {
        // A skipped frame without a timestamp could not be counted (AVI's
        // packed B-frames have none): decode every frame from here on.
        skipping_ = false;
        dec_->skip_frame = AVDISCARD_DEFAULT;
      }
    }
    const int64_t pts = pkt_->pts != AV_NOPTS_VALUE ? pkt_->pts : pkt_->dts;
    if (pts == AV_NOPTS_VALUE) return;
    const int64_t start = fmt_->streams[stream_index_]->start_time;
    const int64_t end = pts + std::max<int64_t>(pkt_->duration, 0);
    read_end_s_ = std::max(read_end_s_, (end - (start != AV_NOPTS_VALUE ? start : 0)) * time_base_s_);
    read_end_pts_s_ = std::max(read_end_pts_s_, end * time_base_s_);
  }

  // The video's length as the container declares it: the stream's duration,
  // else Matroska's per-track DURATION tag, else the file's duration when
  // video is its only stream (an audio track may outlast the video). 0 when
  // unknown. `from_zero` says the length is an end time counted from
  // timestamp 0 rather than from the stream's start: Matroska's tag and a
  // file's duration count from 0, so a remux that kept a broadcast's
  // timestamps (start 11.4 s) declares 15.4 s for 4 s of video.
  double DeclaredVideoDuration(bool* from_zero) const {
    const AVStream* st = fmt_->streams[stream_index_];
    *from_zero = false;
    if (st->duration != AV_NOPTS_VALUE && st->duration > 0) return st->duration * time_base_s_;
    *from_zero = true;
    const AVDictionaryEntry* tag = av_dict_get(st->metadata, "DURATION", nullptr, 0);
    int h = 0, m = 0;
    double s = 0;
    if (tag && std::sscanf(tag->value, "%d:%d:%lf", &h, &m, &s) == 3) return h * 3600.0 + m * 60 + s;
    if (fmt_->nb_streams == 1 && fmt_->duration != AV_NOPTS_VALUE && fmt_->duration > 0)
      return static_cast<double>(fmt_->duration) / AV_TIME_BASE;
    return 0;
  }

  // AVI counts frames in slots of 1/fps and marks a dropped frame by an empty
  // slot (a capture that skipped frames, a variable-rate export): such a file
  // declares more frames than it holds and is whole, for its packets'
  // timestamps reach the last slot. Frames are missing only where the
  // packets end early (a truncated AVI loses its index, and its packets are
  // numbered one slot each).
  bool SlotsHaveGaps() const {
    const int64_t slots = fmt_->streams[stream_index_]->nb_frames;
    if (slots <= 0 || video_packets_ >= slots) return false;
    const double period = info_.fps > 0 ? 1 / info_.fps : 1.0 / 24;
    return read_end_s_ + std::max(0.5, 3 * period) >= static_cast<double>(slots) * period;
  }

  // A file cut short (an interrupted copy or download) ends cleanly for the
  // demuxer, but before what its header declares: an error, not a shorter
  // video (the camera path would silently stop early). Truncated when the
  // video packets end more than max(0.5 s, 3 frames) before the declared
  // length, or over 5 % of the declared frame count is missing (AVI and MP4
  // headers count frames; a truncated AVI loses its index and with it the
  // right duration).
  void CheckNotTruncated() const {
    bool from_zero = false;
    const double declared = DeclaredVideoDuration(&from_zero);
    const double period = info_.fps > 0 ? 1 / info_.fps : 1.0 / 24;
    const int64_t declared_frames = fmt_->streams[stream_index_]->nb_frames;
    // A length counted from 0 is met by the packets' own end time; some
    // muxers still count it from the start, so either reading passes.
    const double read_end = from_zero ? std::max(read_end_s_, read_end_pts_s_) : read_end_s_;
    const bool short_time = declared > 0 && read_end + std::max(0.5, 3 * period) < declared;
    const bool short_count = declared_frames > 0 && !SlotsHaveGaps() &&
                             video_packets_ + 1 < 0.95 * static_cast<double>(declared_frames);
    if (!short_time && !short_count) return;
    char buf[160];
    if (short_time)
      std::snprintf(buf, sizeof buf, "truncated: the video ends at %.2f s of the %.2f s declared",
                    read_end, declared);
    else
      std::snprintf(buf, sizeof buf, "truncated: %ld of the %ld frames declared", video_packets_,
                    static_cast<long>(declared_frames));
    throw Error(info_.path, buf);
  }

  // skip_nonref_frames: every packet read carries a frame's timestamp; the
  // ones before this frame's that no decoded frame took are the frames the
  // decoder skipped. Their packets have all been read by now: a decoder
  // outputs a frame only after the reordering delay, i.e. after every frame
  // that comes before it in presentation order was sent. Timestamps outside
  // (previous frame, this frame) (broken files, before the first frame)
  // are dropped and not counted.
  void IndexAfterSkipped(double previous_time_s, Frame* out) {
    out->skipped_before_s.clear();
    const int64_t pts = FramePts();
    if (pts != AV_NOPTS_VALUE && start_pts_ != AV_NOPTS_VALUE) {
      while (!unseen_pts_.empty() && unseen_pts_.top() < pts) {
        const double t = (unseen_pts_.top() - start_pts_) * time_base_s_;
        unseen_pts_.pop();
        if (decoded_ > 0 && t > previous_time_s && t < out->time_s) {
          out->skipped_before_s.push_back(t);
          ++presented_;
        }
      }
      if (!unseen_pts_.empty() && unseen_pts_.top() == pts) unseen_pts_.pop();
    }
    out->index = static_cast<int>(presented_++);
  }

  // The decoded frame's timestamp (AV_NOPTS_VALUE: none).
  int64_t FramePts() const {
    return frame_->best_effort_timestamp != AV_NOPTS_VALUE ? frame_->best_effort_timestamp : frame_->pts;
  }

  double FrameTime() {
    const int64_t pts = FramePts();
    double t;
    if (pts == AV_NOPTS_VALUE) {
      t = decoded_ == 0 ? 0.0 : last_time_s_ + (info_.fps > 0 ? 1.0 / info_.fps : 1.0 / 24);
    } else {
      if (start_pts_ == AV_NOPTS_VALUE) start_pts_ = pts;
      t = (pts - start_pts_) * time_base_s_;
    }
    // Broken files repeat or reorder timestamps; keep times increasing.
    if (decoded_ > 0 && !(t > last_time_s_))
      t = last_time_s_ + (info_.fps > 0 ? 1.0 / info_.fps : 1.0 / 24);
    last_time_s_ = t;
    return t;
  }

  // Scales frame_ into `dst` (type CV_8UC1 or CV_8UC3, preallocated at the
  // working size) with a cached swscale context.
  void Scale(SwsContext** ctx, AVPixelFormat dst_format, int flags, cv::Mat* dst) {
    const int fw = frame_->width, fh = frame_->height;
    *ctx = sws_getCachedContext(*ctx, fw, fh, static_cast<AVPixelFormat>(frame_->format), dst->cols,
                                dst->rows, dst_format, flags, nullptr, nullptr, nullptr);
    if (!*ctx)
      throw Error(info_.path, std::string("cannot convert pixel format ") +
                                  av_get_pix_fmt_name(static_cast<AVPixelFormat>(frame_->format)));
    cv::Mat target = *dst;
    cv::Mat padded;
    if (!RowsAligned(*dst)) {  // scale into an aligned buffer, then copy
      const int row_bytes = dst->cols * static_cast<int>(dst->elemSize());
      padded.create(dst->rows, (row_bytes + 31) / 32 * 32, CV_8UC1);
      target = cv::Mat(dst->rows, dst->cols, dst->type(), padded.data, padded.step);
    }
    uint8_t* planes[4] = {target.data, nullptr, nullptr, nullptr};
    int strides[4] = {static_cast<int>(target.step), 0, 0, 0};
    sws_scale(*ctx, frame_->data, frame_->linesize, 0, fh, planes, strides);
    if (target.data != dst->data) target.copyTo(*dst);
  }

  // A decoded frame at exactly twice the working size in 8-bit limited-range
  // YUV: the gray image straight from its luma plane, the same bytes as
  // swscale's (half_gray.h) at a fraction of the cost.
  bool HalfGrayApplies(cv::Size work) const {
    const int fw = frame_->width, fh = frame_->height;
    const auto format = static_cast<AVPixelFormat>(frame_->format);
    const bool limited_8bit = format == AV_PIX_FMT_YUV420P || format == AV_PIX_FMT_YUV422P ||
                              format == AV_PIX_FMT_YUV444P || format == AV_PIX_FMT_NV12 ||
                              format == AV_PIX_FMT_NV21;
    return limited_8bit && sar_.num == sar_.den && fw >= 8 && fh >= 8 && work.width * 2 == fw && work.height * 2 == fh &&
           frame_->linesize[0] > 0 && HalfGrayMatchesSwscale();
  }

  // The caller's previous image buffer if nobody else holds it (saves a
  // fresh allocation, i.e. page faults, per frame), else a new one.
  static cv::Mat Reuse(cv::Mat* previous, cv::Size size, int type) {
    cv::Mat m;
    if (previous->u && previous->u->refcount == 1 && previous->isContinuous() &&
        previous->size() == size && previous->type() == type &&
        previous->data == previous->datastart)
      m = *previous;
    previous->release();
    if (m.empty()) m.create(size, type);
    return m;
  }

  void Convert(Frame* out) {
    const int fh = frame_->height;
    const int fw = DisplayWidth(frame_->width, sar_);  // square pixels
    CheckSize(frame_->width, fh);
    CheckSize(fw, fh);
    const cv::Size work = WorkingSize(fw, fh, options_.max_working_side);
    const bool rotate = info_.rotation_deg != 0;
    cv::Mat gray = rotate ? cv::Mat(work, CV_8UC1) : Reuse(&out->gray, work, CV_8UC1);
    // Gray feeds the tracker: proper bilinear filtering (antialiased when
    // shrinking). BGR only feeds shot statistics and previews: the fast
    // path, which roughly halves its cost; a thumbnail (color_max_side) is
    // area-averaged, as fast bilinear would skip most of the picture.
    if (HalfGrayApplies(work))
      HalfGrayFromLimitedLuma(frame_->data[0], frame_->linesize[0], fw, fh, gray.data,
                              static_cast<int>(gray.step));
    else
      Scale(&gray_sws_, AV_PIX_FMT_GRAY8, SWS_BILINEAR, &gray);
    cv::Mat bgr;
    if (options_.want_color) {
      const int side = options_.color_max_side;
      const bool thumb = side > 0 && side < std::max(work.width, work.height);
      const cv::Size color = thumb ? WorkingSize(fw, fh, side) : work;
      bgr = rotate ? cv::Mat(color, CV_8UC3) : Reuse(&out->bgr, color, CV_8UC3);
      Scale(&bgr_sws_, AV_PIX_FMT_BGR24, thumb ? SWS_AREA : SWS_FAST_BILINEAR, &bgr);
    }
    int dec_w = fw, dec_h = fh;
    if (info_.rotation_deg != 0) {
      const int code = info_.rotation_deg == 90    ? cv::ROTATE_90_CLOCKWISE
                       : info_.rotation_deg == 180 ? cv::ROTATE_180
                                                   : cv::ROTATE_90_COUNTERCLOCKWISE;
      cv::Mat g, b;
      cv::rotate(gray, g, code);
      gray = g;
      if (!bgr.empty()) {
        cv::rotate(bgr, b, code);
        bgr = b;
      }
      if (info_.rotation_deg != 180) std::swap(dec_w, dec_h);
    }
    const double previous_time_s = last_time_s_;
    out->time_s = FrameTime();
    if (options_.skip_nonref_frames)  // also after skipping_ stopped: the index counts on
      IndexAfterSkipped(previous_time_s, out);
    else
      out->index = static_cast<int>(decoded_);
    out->gray = gray;
    out->bgr = bgr;
    out->decoded_width = dec_w;
    out->decoded_height = dec_h;
    out->scale = dec_w >= dec_h ? static_cast<double>(gray.cols) / dec_w
                                : static_cast<double>(gray.rows) / dec_h;
  }

  void Close() {
    if (gray_sws_) sws_freeContext(gray_sws_);
    if (bgr_sws_) sws_freeContext(bgr_sws_);
    gray_sws_ = bgr_sws_ = nullptr;
    av_frame_free(&frame_);
    av_packet_free(&pkt_);
    avcodec_free_context(&dec_);
    avformat_close_input(&fmt_);
  }

  FrameSourceOptions options_;
  VideoInfo info_;
  AVFormatContext* fmt_ = nullptr;
  AVCodecContext* dec_ = nullptr;
  AVPacket* pkt_ = nullptr;
  AVFrame* frame_ = nullptr;
  SwsContext* gray_sws_ = nullptr;
  SwsContext* bgr_sws_ = nullptr;
  int stream_index_ = -1;
  AVRational sar_{1, 1};  // sample aspect ratio, applied to every frame
  double time_base_s_ = 0;
  int64_t start_pts_ = AV_NOPTS_VALUE;
  double last_time_s_ = 0;
  long decoded_ = 0;
  long presented_ = 0;  // skip_nonref_frames: frames decoded or skipped so far
  bool skipping_ = false;  // the decoder skips non-reference frames now
  std::vector<double> skipped_at_end_s_;  // SkippedAtEnd()
  std::vector<std::string> warnings_;     // Warnings()
  // skip_nonref_frames: timestamps of the packets read, not yet matched to
  // a decoded frame, smallest first.
  std::priority_queue<int64_t, std::vector<int64_t>, std::greater<int64_t>> unseen_pts_;
  long bad_packets_ = 0;
  long video_packets_ = 0;  // read from the demuxer
  long discarded_packets_ = 0;  // of those, outside the edit list (AV_PKT_FLAG_DISCARD)
  double read_end_s_ = 0;   // end of the latest video packet read, from the stream start
  double read_end_pts_s_ = 0;  // the same end as a timestamp (from time 0)
  bool draining_ = false;
  bool finished_ = false;
};

}  // namespace

std::unique_ptr<FrameSource> OpenFfmpegSource(const std::string& path,
                                              const FrameSourceOptions& options) {
  return std::make_unique<FfmpegSource>(path, options);
}

}  // namespace hapcine
