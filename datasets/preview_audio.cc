#include "datasets/preview_audio.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/audio_fifo.h>
#include <libavutil/channel_layout.h>
#include <libswresample/swresample.h>
}

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <vector>

#include "core/error.h"
#include "extract/av_error.h"

namespace hapcine {
namespace {

struct InputCloser {
  void operator()(AVFormatContext* c) const { avformat_close_input(&c); }
};
using InputPtr = std::unique_ptr<AVFormatContext, InputCloser>;
struct OutputCloser {
  void operator()(AVFormatContext* c) const {
    if (c->pb) avio_closep(&c->pb);
    avformat_free_context(c);
  }
};
using OutputPtr = std::unique_ptr<AVFormatContext, OutputCloser>;
struct CodecFreer {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
using CodecPtr = std::unique_ptr<AVCodecContext, CodecFreer>;
struct PacketFreer {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
using PacketPtr = std::unique_ptr<AVPacket, PacketFreer>;
struct FrameFreer {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
using FramePtr = std::unique_ptr<AVFrame, FrameFreer>;
struct SwrFreer {
  void operator()(SwrContext* s) const { swr_free(&s); }
};
struct FifoFreer {
  void operator()(AVAudioFifo* f) const { av_audio_fifo_free(f); }
};

PacketPtr NewPacket() {
  PacketPtr p(av_packet_alloc());
  if (!p) throw std::bad_alloc();
  return p;
}

InputPtr OpenInput(const std::string& path, const std::string& name) {
  AVFormatContext* ctx = nullptr;
  int rc = avformat_open_input(&ctx, path.c_str(), nullptr, nullptr);
  if (rc < 0) throw Error(name, "cannot open " + path + ": " + AvErrorText(rc));
  InputPtr in(ctx);
  rc = avformat_find_stream_info(ctx, nullptr);
  if (rc < 0) throw Error(name, "cannot read the streams of " + path + ": " + AvErrorText(rc));
  return in;
}

// Codecs an MP4 carries that every player reads; anything else is encoded.
bool Mp4CopiesAudio(AVCodecID id) {
  return id == AV_CODEC_ID_AAC || id == AV_CODEC_ID_MP3 || id == AV_CODEC_ID_AC3 ||
         id == AV_CODEC_ID_EAC3 || id == AV_CODEC_ID_ALAC;
}

// Reads one stream's packets; false at the end of the file.
bool ReadStreamPacket(AVFormatContext* in, int stream, AVPacket* p, const std::string& name) {
  for (;;) {
    const int rc = av_read_frame(in, p);
    if (rc == AVERROR_EOF) return false;
    if (rc < 0) throw Error(name, std::string("cannot read ") + in->url + ": " + AvErrorText(rc));
    if (p->stream_index == stream) return true;
    av_packet_unref(p);
  }
}

// The film's audio stream and the times of the range: film times count from
// the video stream's start, as the frame source's do.
struct FilmAudio {
  AVFormatContext* film = nullptr;
  int stream = -1;
  double video_start_s = 0;
  AudioRange range;
  std::string name;

  AVStream* in() const { return film->streams[stream]; }
  double TimeS(int64_t ts) const { return ts * av_q2d(in()->time_base) - video_start_s; }
  bool PastEnd(double t) const { return range.to_s >= 0 && t >= range.to_s - 1e-9; }
};

FilmAudio FindFilmAudio(AVFormatContext* film, const AudioRange& range, const std::string& name) {
  FilmAudio a{film, av_find_best_stream(film, AVMEDIA_TYPE_AUDIO, -1, -1, nullptr, 0), 0, range,
              name};
  if (a.stream < 0) throw Error(name, std::string(film->url) + " has no audio stream");
  const int v = av_find_best_stream(film, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (v >= 0 && film->streams[v]->start_time != AV_NOPTS_VALUE)
    a.video_start_s = film->streams[v]->start_time * av_q2d(film->streams[v]->time_base);
  return a;
}

// Packets of one output stream in time order, in that stream's time base.
class PacketSource {
 public:
  virtual ~PacketSource() = default;
  virtual bool Next(AVPacket* p) = 0;  // false at the end
};

// The rendered video's packets, as they are.
class VideoCopy : public PacketSource {
 public:
  VideoCopy(AVFormatContext* in, AVStream* out, std::string name)
      : in_(in), out_(out), name_(std::move(name)) {}
  bool Next(AVPacket* p) override {
    if (!ReadStreamPacket(in_, 0, p, name_)) return false;
    av_packet_rescale_ts(p, in_->streams[0]->time_base, out_->time_base);
    p->stream_index = out_->index;
    p->pos = -1;
    return true;
  }

 private:
  AVFormatContext* in_;
  AVStream* out_;
  std::string name_;
};

// The film's audio packets that start inside the range, shifted to from_s = 0.
class AudioCopy : public PacketSource {
 public:
  AudioCopy(const FilmAudio& film, AVStream* out) : film_(film), out_(out) {
    offset_ = std::llround((film.video_start_s + film.range.from_s) / av_q2d(film.in()->time_base));
  }
  bool Next(AVPacket* p) override {
    while (ReadStreamPacket(film_.film, film_.stream, p, film_.name)) {
      const int64_t ts = p->pts != AV_NOPTS_VALUE ? p->pts : p->dts;
      const double t = ts == AV_NOPTS_VALUE ? -1e300 : film_.TimeS(ts);
      if (film_.PastEnd(t)) {
        av_packet_unref(p);
        return false;
      }
      if (t < film_.range.from_s - 1e-6) {
        av_packet_unref(p);
        continue;
      }
      // Audio is never reordered: a packet without one time has it in the other.
      if (p->pts == AV_NOPTS_VALUE) p->pts = p->dts;
      if (p->dts == AV_NOPTS_VALUE) p->dts = p->pts;
      p->pts = std::max<int64_t>(0, p->pts - offset_);
      p->dts = std::max<int64_t>(0, p->dts - offset_);
      av_packet_rescale_ts(p, film_.in()->time_base, out_->time_base);
      p->stream_index = out_->index;
      p->pos = -1;
      return true;
    }
    return false;
  }

 private:
  FilmAudio film_;
  AVStream* out_;
  int64_t offset_ = 0;
};

// The film's audio decoded, cut to the range's samples and encoded as AAC.
class AudioEncode : public PacketSource {
 public:
  AudioEncode(const FilmAudio& film, AVFormatContext* out_format, AVStream* out);
  bool Next(AVPacket* p) override {
    while (ready_.empty() && !finished_) Pull();
    if (ready_.empty()) return false;
    av_packet_move_ref(p, ready_.front().get());
    ready_.pop_front();
    return true;
  }

 private:
  void OpenDecoder();
  void OpenEncoder(AVFormatContext* out_format);
  void Pull();
  void Drain();           // decoded frames -> Take
  bool Take(AVFrame* f);  // false once past the range's end
  void WriteSamples(float* const* planes, int offset, int count, double t_s);
  void EncodeFifo(bool flush);
  void Encode(AVFrame* f);  // nullptr flushes
  void Finish();

  FilmAudio film_;
  AVStream* out_;
  CodecPtr decoder_, encoder_;
  std::unique_ptr<SwrContext, SwrFreer> swr_;
  std::unique_ptr<AVAudioFifo, FifoFreer> fifo_;
  FramePtr decoded_;
  std::deque<PacketPtr> ready_;
  std::vector<std::vector<float>> planes_;
  int64_t next_pts_ = -1;  // encoder samples; set by the first kept sample
  double next_time_s_ = 0;  // where a frame without a timestamp starts
  bool past_end_ = false, finished_ = false;
};

AudioEncode::AudioEncode(const FilmAudio& film, AVFormatContext* out_format, AVStream* out)
    : film_(film), out_(out), decoded_(av_frame_alloc()) {
  if (!decoded_) throw std::bad_alloc();
  OpenDecoder();
  OpenEncoder(out_format);
}

void AudioEncode::OpenDecoder() {
  const AVCodecParameters* par = film_.in()->codecpar;
  const AVCodec* codec = avcodec_find_decoder(par->codec_id);
  if (!codec) throw Error(film_.name, std::string("no decoder for the film's audio (") +
                                          avcodec_get_name(par->codec_id) + ")");
  decoder_.reset(avcodec_alloc_context3(codec));
  if (!decoder_) throw std::bad_alloc();
  int rc = avcodec_parameters_to_context(decoder_.get(), par);
  if (rc >= 0) rc = avcodec_open2(decoder_.get(), codec, nullptr);
  if (rc < 0) throw Error(film_.name, "cannot open the film's audio decoder: " + AvErrorText(rc));
}

// The film's rate when AAC has it (8 to 96 kHz), else 48 kHz.
int AacRate(const AVCodec* codec, int rate) {
  for (const int* r = codec->supported_samplerates; r && *r; ++r)
    if (*r == rate) return rate;
  return 48000;
}

void AudioEncode::OpenEncoder(AVFormatContext* out_format) {
  const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_AAC);
  if (!codec) throw Error(film_.name, "FFmpeg has no AAC encoder");
  encoder_.reset(avcodec_alloc_context3(codec));
  if (!encoder_) throw std::bad_alloc();
  const int channels = film_.in()->codecpar->ch_layout.nb_channels >= 2 ? 2 : 1;
  av_channel_layout_default(&encoder_->ch_layout, channels);
  encoder_->sample_fmt = AV_SAMPLE_FMT_FLTP;
  encoder_->sample_rate = AacRate(codec, film_.in()->codecpar->sample_rate);
  encoder_->bit_rate = 96000 * channels;
  encoder_->time_base = AVRational{1, encoder_->sample_rate};
  if (out_format->oformat->flags & AVFMT_GLOBALHEADER)
    encoder_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  int rc = avcodec_open2(encoder_.get(), codec, nullptr);
  if (rc >= 0) rc = avcodec_parameters_from_context(out_->codecpar, encoder_.get());
  if (rc < 0) throw Error(film_.name, "cannot open the AAC encoder: " + AvErrorText(rc));
  out_->time_base = encoder_->time_base;
  fifo_.reset(av_audio_fifo_alloc(AV_SAMPLE_FMT_FLTP, channels, 4 * encoder_->frame_size + 1));
  if (!fifo_) throw std::bad_alloc();
  planes_.resize(channels);
}

void AudioEncode::Pull() {
  PacketPtr p = NewPacket();
  if (past_end_ || !ReadStreamPacket(film_.film, film_.stream, p.get(), film_.name)) {
    Finish();
    return;
  }
  // A damaged packet is skipped, as a player would; the next one decodes.
  if (avcodec_send_packet(decoder_.get(), p.get()) >= 0) Drain();
}

void AudioEncode::Drain() {
  while (avcodec_receive_frame(decoder_.get(), decoded_.get()) >= 0) {
    if (!past_end_ && !Take(decoded_.get())) past_end_ = true;
    av_frame_unref(decoded_.get());
  }
}

bool AudioEncode::Take(AVFrame* f) {
  const int64_t ts = f->best_effort_timestamp;
  const double t0 = ts != AV_NOPTS_VALUE ? film_.TimeS(ts) : next_time_s_;
  if (film_.PastEnd(t0)) return false;
  if (!swr_) {
    AVChannelLayout in_layout;
    if (f->ch_layout.order == AV_CHANNEL_ORDER_UNSPEC)
      av_channel_layout_default(&in_layout, f->ch_layout.nb_channels);
    else
      av_channel_layout_copy(&in_layout, &f->ch_layout);
    SwrContext* s = nullptr;
    int rc = swr_alloc_set_opts2(&s, &encoder_->ch_layout, AV_SAMPLE_FMT_FLTP,
                                 encoder_->sample_rate, &in_layout,
                                 static_cast<AVSampleFormat>(f->format), f->sample_rate, 0, nullptr);
    av_channel_layout_uninit(&in_layout);
    swr_.reset(s);
    if (rc >= 0) rc = swr_init(s);
    if (rc < 0) throw Error(film_.name, "cannot convert the film's audio: " + AvErrorText(rc));
  }
  const int capacity = swr_get_out_samples(swr_.get(), f->nb_samples);
  std::vector<float*> out(planes_.size());
  for (size_t c = 0; c < planes_.size(); ++c) {
    planes_[c].resize(std::max(capacity, 1));
    out[c] = planes_[c].data();
  }
  const int n = swr_convert(swr_.get(), reinterpret_cast<uint8_t**>(out.data()), capacity,
                            const_cast<const uint8_t**>(f->extended_data), f->nb_samples);
  if (n < 0) throw Error(film_.name, "cannot convert the film's audio: " + AvErrorText(n));
  const double rate = encoder_->sample_rate;
  next_time_s_ = t0 + n / rate;
  const auto sample_at = [&](double t) {
    return static_cast<int>(std::clamp<double>(std::llround((t - t0) * rate), 0, n));
  };
  const int first = sample_at(film_.range.from_s);
  const int end = film_.range.to_s >= 0 ? sample_at(film_.range.to_s) : n;
  if (end > first) WriteSamples(out.data(), first, end - first, t0 + first / rate);
  return !film_.PastEnd(next_time_s_);
}

void AudioEncode::WriteSamples(float* const* planes, int offset, int count, double t_s) {
  // The first kept sample sets the output clock: an audio stream that starts
  // after from_s starts as late in the preview.
  if (next_pts_ < 0)
    next_pts_ = std::max<int64_t>(0, std::llround((t_s - film_.range.from_s) * encoder_->sample_rate));
  std::vector<float*> at(planes_.size());
  for (size_t c = 0; c < at.size(); ++c) at[c] = planes[c] + offset;
  if (av_audio_fifo_write(fifo_.get(), reinterpret_cast<void**>(at.data()), count) < count)
    throw std::bad_alloc();
  EncodeFifo(false);
}

void AudioEncode::EncodeFifo(bool flush) {
  const int frame_size = encoder_->frame_size;
  while (av_audio_fifo_size(fifo_.get()) >= frame_size ||
         (flush && av_audio_fifo_size(fifo_.get()) > 0)) {
    FramePtr f(av_frame_alloc());
    if (!f) throw std::bad_alloc();
    f->nb_samples = std::min(frame_size, av_audio_fifo_size(fifo_.get()));
    f->format = AV_SAMPLE_FMT_FLTP;
    f->sample_rate = encoder_->sample_rate;
    av_channel_layout_copy(&f->ch_layout, &encoder_->ch_layout);
    if (av_frame_get_buffer(f.get(), 0) < 0) throw std::bad_alloc();
    av_audio_fifo_read(fifo_.get(), reinterpret_cast<void**>(f->data), f->nb_samples);
    f->pts = next_pts_;
    next_pts_ += f->nb_samples;
    Encode(f.get());
  }
}

void AudioEncode::Encode(AVFrame* f) {
  int rc = avcodec_send_frame(encoder_.get(), f);
  if (rc < 0) throw Error(film_.name, "the AAC encoder rejected audio: " + AvErrorText(rc));
  for (;;) {
    PacketPtr p = NewPacket();
    rc = avcodec_receive_packet(encoder_.get(), p.get());
    if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
    if (rc < 0) throw Error(film_.name, "AAC encoding failed: " + AvErrorText(rc));
    av_packet_rescale_ts(p.get(), encoder_->time_base, out_->time_base);
    p->stream_index = out_->index;
    ready_.push_back(std::move(p));
  }
}

void AudioEncode::Finish() {
  if (!past_end_ && avcodec_send_packet(decoder_.get(), nullptr) >= 0) Drain();
  EncodeFifo(true);
  Encode(nullptr);
  finished_ = true;
}

// Writes packets from both sources in time order, so the muxer never holds
// more than a few: a two-hour film is never buffered whole.
void Interleave(AVFormatContext* out, PacketSource* video, PacketSource* audio,
                const std::string& name) {
  PacketSource* sources[2] = {video, audio};
  PacketPtr pending[2] = {NewPacket(), NewPacket()};
  bool has[2] = {video->Next(pending[0].get()), audio->Next(pending[1].get())};
  while (has[0] || has[1]) {
    int k = has[0] ? 0 : 1;
    if (has[0] && has[1]) {
      const AVRational tb0 = out->streams[pending[0]->stream_index]->time_base;
      const AVRational tb1 = out->streams[pending[1]->stream_index]->time_base;
      k = av_compare_ts(pending[0]->dts, tb0, pending[1]->dts, tb1) <= 0 ? 0 : 1;
    }
    const int rc = av_interleaved_write_frame(out, pending[k].get());  // takes the data
    if (rc < 0) throw Error(name, "write failed (disk full?): " + AvErrorText(rc));
    has[k] = sources[k]->Next(pending[k].get());
  }
}

}  // namespace

bool FilmHasAudio(const std::string& film) {
  AVFormatContext* ctx = nullptr;
  if (avformat_open_input(&ctx, film.c_str(), nullptr, nullptr) < 0) return false;
  const InputPtr in(ctx);
  if (avformat_find_stream_info(ctx, nullptr) < 0) return false;
  return av_find_best_stream(ctx, AVMEDIA_TYPE_AUDIO, -1, -1, nullptr, 0) >= 0;
}

std::string MuxFilmAudio(const std::string& video_only, const std::string& film,
                         const AudioRange& range, const std::string& output_path,
                         const std::string& error_name) {
  const InputPtr video = OpenInput(video_only, error_name);
  const InputPtr source = OpenInput(film, error_name);
  if (video->nb_streams < 1) throw Error(error_name, video_only + " has no video stream");
  const FilmAudio audio = FindFilmAudio(source.get(), range, error_name);
  AVFormatContext* raw = nullptr;
  int rc = avformat_alloc_output_context2(&raw, nullptr, "mp4", output_path.c_str());
  if (rc < 0 || !raw) throw Error(error_name, "cannot create MP4 muxer: " + AvErrorText(rc));
  const OutputPtr out(raw);
  AVStream* video_out = avformat_new_stream(raw, nullptr);
  AVStream* audio_out = avformat_new_stream(raw, nullptr);
  if (!video_out || !audio_out) throw std::bad_alloc();
  rc = avcodec_parameters_copy(video_out->codecpar, video->streams[0]->codecpar);
  if (rc < 0) throw Error(error_name, "codec parameters: " + AvErrorText(rc));
  video_out->codecpar->codec_tag = 0;
  video_out->time_base = video->streams[0]->time_base;
  video_out->avg_frame_rate = video->streams[0]->avg_frame_rate;
  std::unique_ptr<PacketSource> audio_source;
  const bool copy = Mp4CopiesAudio(audio.in()->codecpar->codec_id);
  if (copy) {
    rc = avcodec_parameters_copy(audio_out->codecpar, audio.in()->codecpar);
    if (rc < 0) throw Error(error_name, "codec parameters: " + AvErrorText(rc));
    audio_out->codecpar->codec_tag = 0;
    audio_out->time_base = audio.in()->time_base;
    audio_source = std::make_unique<AudioCopy>(audio, audio_out);
  } else {
    audio_source = std::make_unique<AudioEncode>(audio, raw, audio_out);
  }
  rc = avio_open(&raw->pb, output_path.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) throw Error(error_name, "cannot open for writing: " + AvErrorText(rc));
  rc = avformat_write_header(raw, nullptr);
  if (rc < 0) throw Error(error_name, "cannot write MP4 header: " + AvErrorText(rc));
  VideoCopy video_source(video.get(), video_out, error_name);
  Interleave(raw, &video_source, audio_source.get(), error_name);
  rc = av_write_trailer(raw);
  if (rc < 0) throw Error(error_name, "cannot finish MP4: " + AvErrorText(rc));
  rc = avio_closep(&raw->pb);
  if (rc < 0) throw Error(error_name, "cannot close file: " + AvErrorText(rc));
  return copy ? "copy" : "aac";
}

}  // namespace hapcine
