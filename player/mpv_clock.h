#pragma once
// The video player and its media clock: libmpv plays the film (window,
// sound, mpv's own keys and on-screen controller: space pauses, arrows seek,
// f toggles full screen, q quits), and an event thread turns mpv's
// "time-pos", "pause", "speed", "eof-reached" notifications plus its seek
// events into ClockReadings for the haptic loop.
//
// While mpv seeks (MPV_EVENT_SEEK .. MPV_EVENT_PLAYBACK_RESTART) the clock
// reads as paused at the last position, so the loop holds rather than
// extrapolating through a seek; the seek serial then makes the loop ramp to
// the new position. Headless mode: vo=null, ao=null (same clock, no window).

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "player/media_clock.h"

struct mpv_handle;

namespace hapcine {

struct MpvApi;

struct MpvOptions {
  bool headless = false;  // vo=null, ao=null
  bool fullscreen = false;
  bool keep_open = true;  // keep the last frame at the end (user may seek back)
  bool start_paused = false;
};

class MpvClock : public MediaClock {
 public:
  // Starts mpv and loads `video`. Throws hapcine::Error if libmpv cannot be
  // loaded or mpv cannot start.
  MpvClock(const std::string& video, const MpvOptions& options);
  ~MpvClock() override;
  MpvClock(const MpvClock&) = delete;
  MpvClock& operator=(const MpvClock&) = delete;

  // Waits until the file is loaded; throws Error(video, reason) if mpv
  // could not open it or it did not load within timeout_s.
  void WaitLoaded(double timeout_s);
  // Duration reported by mpv (seconds); < 0 if unknown.
  double duration_s() const { return duration_s_.load(); }
  // Commands (thread-safe): pause, relative seek, quit.
  void SetPause(bool paused);
  void SeekAbsolute(double media_s);
  void Quit();

  ClockReading Read() const noexcept override { return cell_.Load(); }

 private:
  void EventLoop();
  void Publish();

  std::string video_;
  const MpvApi* api_;  // libmpv, opened on first use (player/mpv_library.h)
  mpv_handle* mpv_ = nullptr;
  std::thread events_;
  ClockCell cell_;
  // Event-thread state (only the event thread touches these after start).
  ClockReading r_;
  bool user_paused_ = false, seeking_ = true;
  std::atomic<double> duration_s_{-1};
  std::atomic<int> load_state_{0};  // 0 loading, 1 loaded, -1 failed
  std::mutex error_mutex_;
  std::string load_error_;
};

}  // namespace hapcine
