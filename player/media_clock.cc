#include "player/media_clock.h"

#include <time.h>

#include <algorithm>
#include <cmath>

namespace hapcine {

double SteadySeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double Extrapolate(const ClockReading& r, double now_s, double max_ahead_s) {
  if (!r.valid || r.paused || !std::isfinite(now_s)) return r.media_s;
  const double ahead = std::clamp(now_s - r.wall_s, 0.0, max_ahead_s);
  return r.media_s + r.rate * ahead;
}

namespace {
constexpr uint32_t kPaused = 1, kEof = 2, kFinished = 4, kValid = 8;
}

void ClockCell::Store(const ClockReading& r) noexcept {
  const uint64_t s = seq_.load(std::memory_order_relaxed);
  seq_.store(s + 1, std::memory_order_relaxed);  // odd: writing
  std::atomic_thread_fence(std::memory_order_release);
  media_s_.store(r.media_s, std::memory_order_relaxed);
  wall_s_.store(r.wall_s, std::memory_order_relaxed);
  rate_.store(r.rate, std::memory_order_relaxed);
  serial_.store(r.serial, std::memory_order_relaxed);
  seek_serial_.store(r.seek_serial, std::memory_order_relaxed);
  flags_.store((r.paused ? kPaused : 0) | (r.eof ? kEof : 0) | (r.finished ? kFinished : 0) |
                   (r.valid ? kValid : 0),
               std::memory_order_relaxed);
  seq_.store(s + 2, std::memory_order_release);
}

ClockReading ClockCell::Load() const noexcept {
  ClockReading r;
  for (;;) {
    const uint64_t s0 = seq_.load(std::memory_order_acquire);
    if (s0 & 1) continue;  // a write is in progress (a few ns)
    r.media_s = media_s_.load(std::memory_order_relaxed);
    r.wall_s = wall_s_.load(std::memory_order_relaxed);
    r.rate = rate_.load(std::memory_order_relaxed);
    r.serial = serial_.load(std::memory_order_relaxed);
    r.seek_serial = seek_serial_.load(std::memory_order_relaxed);
    const uint32_t f = flags_.load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (seq_.load(std::memory_order_relaxed) != s0) continue;
    r.paused = f & kPaused;
    r.eof = f & kEof;
    r.finished = f & kFinished;
    r.valid = f & kValid;
    return r;
  }
}

void FakeClock::Update(double media_s, double wall_s, bool paused, double rate) {
  last_.media_s = media_s;
  last_.wall_s = wall_s;
  last_.paused = paused;
  last_.rate = rate;
  last_.valid = true;
  ++last_.serial;
  cell_.Store(last_);
}

void FakeClock::Seek(double media_s, double wall_s) {
  ++last_.seek_serial;
  last_.eof = false;
  Update(media_s, wall_s, last_.paused, last_.rate);
}

void FakeClock::SetEof(double wall_s) {
  last_.eof = true;
  Update(last_.media_s, wall_s, last_.paused, last_.rate);
}

void FakeClock::Finish() {
  last_.finished = true;
  ++last_.serial;
  cell_.Store(last_);
}

bool FakeClock::TrueMediaTime(double now_s, double* media_s) const noexcept {
  if (!has_truth_) return false;
  *media_s = truth_media0_ + truth_rate_ * now_s;
  return true;
}

WallClock::WallClock(double duration_s, double start_media_s, bool held)
    : duration_s_(duration_s),
      start_media_s_(start_media_s),
      start_wall_s_(SteadySeconds()),
      held_(held) {}

void WallClock::Start(double now_s) {
  start_wall_s_.store(now_s);
  held_.store(false);
}

ClockReading WallClock::Read() const noexcept {
  ClockReading r;
  const double now = SteadySeconds();
  if (held_.load(std::memory_order_relaxed)) {
    r.media_s = start_media_s_;
    r.wall_s = now;
    r.valid = true;
    r.paused = true;
    r.serial = 1;
    return r;
  }
  double t = 0;
  TrueMediaTime(now, &t);
  r.media_s = std::min(t, duration_s_);
  r.wall_s = now;
  r.paused = false;
  r.valid = true;
  r.eof = t >= duration_s_;
  r.serial = static_cast<uint64_t>(now * 1e6);
  return r;
}

bool WallClock::TrueMediaTime(double now_s, double* media_s) const noexcept {
  if (held_.load(std::memory_order_relaxed)) {
    *media_s = start_media_s_;
    return true;
  }
  *media_s = start_media_s_ + (now_s - start_wall_s_.load(std::memory_order_relaxed));
  return true;
}

}  // namespace hapcine
