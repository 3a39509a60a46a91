#pragma once
// Where the video is: the media clock the 1 kHz loop follows.
//
// A clock publishes readings (media time at a wall-clock instant, rate,
// paused, eof). Players update a few dozen times a second (mpv: once per
// frame); the loop extrapolates between updates:
//   media(now) = media_s + rate * (now - wall_s)   (held while paused).
// Readings cross threads through ClockCell, a seqlock over atomics: the
// writer (mpv's event thread) never blocks the reader (the tick), and the
// reader never sees a torn reading.
//
// Wall time everywhere is SteadySeconds(): CLOCK_MONOTONIC in seconds, the
// same clock the loop sleeps on.

#include <atomic>
#include <cstdint>

namespace hapcine {

double SteadySeconds();

struct ClockReading {
  double media_s = 0;  // media time at the update
  double wall_s = 0;   // SteadySeconds() at the update
  double rate = 1;     // playback speed
  bool paused = true;
  bool eof = false;          // playback reached the end of the file
  bool finished = false;     // the player is gone (window closed, quit)
  bool valid = false;        // a media time has been seen
  uint64_t serial = 0;       // increments with every update
  uint64_t seek_serial = 0;  // increments with every seek
};

// Media time at `now_s` from `r` (no further than max_ahead_s past the
// update, so a stalled clock cannot run away).
double Extrapolate(const ClockReading& r, double now_s, double max_ahead_s = 1.0);

class ClockCell {
 public:
  void Store(const ClockReading& r) noexcept;
  ClockReading Load() const noexcept;

 private:
  std::atomic<uint64_t> seq_{0};
  std::atomic<double> media_s_{0}, wall_s_{0}, rate_{1};
  std::atomic<uint64_t> serial_{0}, seek_serial_{0};
  std::atomic<uint32_t> flags_{0};
};

class MediaClock {
 public:
  virtual ~MediaClock() = default;
  // Latest reading. Real-time safe (lock-free, no allocation).
  virtual ClockReading Read() const noexcept = 0;
  // The true media time at wall time `now_s`, when the clock knows it
  // exactly (tests, WallClock): used to measure the loop's sync error.
  virtual bool TrueMediaTime(double now_s, double* media_s) const noexcept { return false; }
};

// Tests drive it by hand: Update(...) as a player would.
class FakeClock : public MediaClock {
 public:
  // Publishes an update at wall time wall_s.
  void Update(double media_s, double wall_s, bool paused = false, double rate = 1.0);
  void Seek(double media_s, double wall_s);
  void SetEof(double wall_s);
  void Finish();
  // Exact media time for the sync-error measurement (set by the test).
  void SetTruth(double media_at_wall0, double rate) {
    truth_media0_ = media_at_wall0, truth_rate_ = rate, has_truth_ = true;
  }
  ClockReading Read() const noexcept override { return cell_.Load(); }
  bool TrueMediaTime(double now_s, double* media_s) const noexcept override;

 private:
  ClockCell cell_;
  ClockReading last_;
  double truth_media0_ = 0, truth_rate_ = 1;
  bool has_truth_ = false;
};

// Media time = wall time since Start(), for playing a track without video
// (sim device, benchmarks). Reaches eof at `duration_s`. Runs from
// construction unless `held`: then it reads as paused at start_media_s until
// Start() (the player holds the film while Falcons are homed).
class WallClock : public MediaClock {
 public:
  explicit WallClock(double duration_s, double start_media_s = 0, bool held = false);
  void Start(double now_s);  // default: at construction
  ClockReading Read() const noexcept override;
  bool TrueMediaTime(double now_s, double* media_s) const noexcept override;

 private:
  double duration_s_, start_media_s_;
  std::atomic<double> start_wall_s_;
  std::atomic<bool> held_;
};

}  // namespace hapcine
