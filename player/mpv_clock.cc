#include "player/mpv_clock.h"

#include <chrono>

#include "core/error.h"
#include "player/mpv_library.h"

namespace hapcine {
namespace {
enum : uint64_t { kTimePos = 1, kPause, kSpeed, kEof, kDuration };
}

MpvClock::MpvClock(const std::string& video, const MpvOptions& o) : video_(video), api_(&Mpv()) {
  mpv_ = api_->create();
  if (!mpv_) throw Error(video, "cannot create the mpv player (libmpv)");
  auto set = [&](const char* k, const char* v) {
    const int rc = api_->set_option_string(mpv_, k, v);
    if (rc < 0) {
      api_->terminate_destroy(mpv_);
      mpv_ = nullptr;
      throw Error(video, std::string("mpv option ") + k + "=" + v + ": " + api_->error_string(rc));
    }
  };
  if (o.headless) {
    set("vo", "null");
    set("ao", "null");
  } else {
    set("input-default-bindings", "yes");
    set("input-vo-keyboard", "yes");
    set("osc", "yes");
    set("force-window", "yes");
    if (o.fullscreen) set("fullscreen", "yes");
  }
  set("keep-open", o.keep_open ? "yes" : "no");
  set("terminal", "no");
  if (o.start_paused) set("pause", "yes");
  const int rc = api_->initialize(mpv_);
  if (rc < 0) {
    api_->terminate_destroy(mpv_);
    mpv_ = nullptr;
    throw Error(video, std::string("cannot initialise mpv: ") + api_->error_string(rc));
  }
  api_->observe_property(mpv_, kTimePos, "time-pos", MPV_FORMAT_DOUBLE);
  api_->observe_property(mpv_, kPause, "pause", MPV_FORMAT_FLAG);
  api_->observe_property(mpv_, kSpeed, "speed", MPV_FORMAT_DOUBLE);
  api_->observe_property(mpv_, kEof, "eof-reached", MPV_FORMAT_FLAG);
  api_->observe_property(mpv_, kDuration, "duration", MPV_FORMAT_DOUBLE);
  r_.paused = true;
  cell_.Store(r_);
  events_ = std::thread([this] { EventLoop(); });
  const char* cmd[] = {"loadfile", video_.c_str(), nullptr};
  const int lrc = api_->command(mpv_, cmd);
  if (lrc < 0) {
    load_state_ = -1;
    std::lock_guard<std::mutex> lock(error_mutex_);
    load_error_ = std::string("mpv loadfile: ") + api_->error_string(lrc);
  }
}

MpvClock::~MpvClock() {
  if (mpv_) {
    const char* cmd[] = {"quit", nullptr};
    api_->command(mpv_, cmd);
    api_->wakeup(mpv_);
  }
  if (events_.joinable()) events_.join();
  if (mpv_) api_->terminate_destroy(mpv_);
}

void MpvClock::WaitLoaded(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (load_state_.load() == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (load_state_.load() == 1) return;
  std::lock_guard<std::mutex> lock(error_mutex_);
  throw Error(video_, load_state_.load() == 0
                          ? "mpv did not load the file within " + std::to_string(timeout_s) + " s"
                          : (load_error_.empty() ? "mpv cannot play this file" : load_error_));
}

void MpvClock::SetPause(bool paused) {
  int flag = paused ? 1 : 0;
  api_->set_property(mpv_, "pause", MPV_FORMAT_FLAG, &flag);
}

void MpvClock::SeekAbsolute(double media_s) {
  const std::string t = std::to_string(media_s);
  const char* cmd[] = {"seek", t.c_str(), "absolute", nullptr};
  api_->command(mpv_, cmd);
}

void MpvClock::Quit() {
  const char* cmd[] = {"quit", nullptr};
  api_->command(mpv_, cmd);
}

void MpvClock::Publish() {
  r_.paused = user_paused_ || seeking_;
  r_.wall_s = SteadySeconds();
  ++r_.serial;
  cell_.Store(r_);
}

void MpvClock::EventLoop() {
  for (;;) {
    mpv_event* ev = api_->wait_event(mpv_, 1.0);
    switch (ev->event_id) {
      case MPV_EVENT_SHUTDOWN:
        r_.finished = true;
        Publish();
        if (load_state_.load() == 0) {
          std::lock_guard<std::mutex> lock(error_mutex_);
          load_error_ = "mpv shut down before the file loaded";
          load_state_ = -1;
        }
        return;
      case MPV_EVENT_FILE_LOADED:
        load_state_ = 1;
        break;
      case MPV_EVENT_END_FILE: {
        const auto* end = static_cast<mpv_event_end_file*>(ev->data);
        if (end->reason == MPV_END_FILE_REASON_ERROR && load_state_.load() == 0) {
          std::lock_guard<std::mutex> lock(error_mutex_);
          load_error_ = std::string("mpv cannot play it: ") + api_->error_string(end->error);
          load_state_ = -1;
        }
        r_.eof = true;
        Publish();
        break;
      }
      case MPV_EVENT_SEEK:
        seeking_ = true;
        ++r_.seek_serial;
        Publish();
        break;
      case MPV_EVENT_PLAYBACK_RESTART:
        seeking_ = false;
        Publish();
        break;
      case MPV_EVENT_PROPERTY_CHANGE: {
        const auto* p = static_cast<mpv_event_property*>(ev->data);
        if (p->format == MPV_FORMAT_NONE) break;
        switch (ev->reply_userdata) {
          case kTimePos:
            r_.media_s = *static_cast<double*>(p->data);
            r_.valid = true;
            break;
          case kPause:
            user_paused_ = *static_cast<int*>(p->data) != 0;
            break;
          case kSpeed:
            r_.rate = *static_cast<double*>(p->data);
            break;
          case kEof:
            r_.eof = *static_cast<int*>(p->data) != 0;
            break;
          case kDuration:
            duration_s_ = *static_cast<double*>(p->data);
            break;
        }
        Publish();
        break;
      }
      default:
        break;
    }
  }
}

}  // namespace hapcine
