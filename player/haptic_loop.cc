#include "player/haptic_loop.h"

#include <cmath>
#include <ostream>

#include "core/error.h"

namespace hapcine {

void LoopOptions::Check() const {
  if (!(rate_hz >= 100 && rate_hz <= 10000))
    throw UsageError("loop rate_hz must be in [100, 10000]");
  if (!(k_n_m >= 0 && k_n_m <= 3000))
    throw UsageError("--k must be in [0, 3000] N/m (a Falcon is stable to ~1000)");
  if (!(d_n_s_m >= 0 && d_n_s_m <= 50)) throw UsageError("--d must be in [0, 50] N s/m");
  if (!(seek_ramp_s > 0 && seek_ramp_s <= 10))
    throw UsageError("loop seek_ramp_s must be in (0, 10]");
  if (!(start_ramp_s > 0 && start_ramp_s <= 10))
    throw UsageError("loop start_ramp_s must be in (0, 10]");
  if (!(end_ramp_s > 0 && end_ramp_s <= 10)) throw UsageError("loop end_ramp_s must be in (0, 10]");
  if (!(seek_jump_s > 0)) throw UsageError("loop seek_jump_s must be > 0");
  safety.Check();
}

HapticLoop::HapticLoop(const HapticTrack& track, HapSeat& seat, const MediaClock& clock,
                       LoopOptions options)
    : track_(track),
      seat_(seat),
      clock_(clock),
      o_(options),
      watchdog_(options.safety),
      ring_(2048) {
  o_.Check();
  for (int a = 0; a < kNumActuators; ++a) {
    const double dev_max = seat_.devices[a] ? seat_.devices[a]->MaxForceN() : 0.0;
    safety_[a] = ActuatorSafety(o_.safety, dev_max);
    target_m_[a].setZero();
    force_n_[a].setZero();
    ramp_from_m_[a].setZero();
  }
  stats_.nominal_period_s = 1.0 / o_.rate_hz;
}

void HapticLoop::StartRamp(int a, double now_s, double len_s) {
  ramp_from_m_[a] = target_m_[a];
  ramp_start_s_[a] = now_s;
  ramp_len_s_[a] = len_s;
}

void HapticLoop::ZeroAll() noexcept {
  for (int a = 0; a < kNumActuators; ++a) {
    force_n_[a].setZero();
    safety_[a].ResetForce();
    if (!seat_.devices[a]) continue;
    try {
      seat_.devices[a]->Exchange(Eigen::Vector3d::Zero());
    } catch (...) {
    }
  }
}

bool HapticLoop::Fail(const char* why) {
  ZeroAll();
  status_ = LoopStatus::kFaulted;
  fault_ = why;
  return false;
}

double HapticLoop::RecordTiming(double now_s) {
  double dt = 0;
  if (have_last_tick_) {
    dt = now_s - last_tick_s_;
    stats_.period.Add(dt);
    const double periods = dt * o_.rate_hz;
    if (periods > 1.5) stats_.missed_ticks += static_cast<int64_t>(std::lround(periods)) - 1;
  } else {
    stats_.first_tick_s = now_s;
  }
  have_last_tick_ = true;
  last_tick_s_ = now_s;
  stats_.last_tick_s = now_s;
  ++stats_.ticks;
  return dt;
}

// A new reading whose seek serial changed, or whose time jumps away from the
// previous reading's extrapolation, is a seek.
bool HapticLoop::ReadClockSeek(ClockReading* reading) {
  const ClockReading& r = *reading = clock_.Read();
  if (!r.valid || r.serial == prev_reading_.serial) return false;
  bool seek = false;
  if (prev_reading_.valid) {
    const double predicted = Extrapolate(prev_reading_, r.wall_s);
    const double jump = r.media_s - predicted;
    double truth = 0;
    if (r.seek_serial != prev_reading_.seek_serial || std::abs(jump) > o_.seek_jump_s) {
      seek = true;
      ++stats_.seeks;
    } else if (!prev_reading_.paused && !r.paused && !clock_.TrueMediaTime(r.wall_s, &truth)) {
      // A clock without ground truth (mpv): the sync error is how far
      // our extrapolated time was from the time the player reports.
      stats_.extrapolation_error.Add(jump);
    }
  }
  prev_reading_ = r;
  return seek;
}

void HapticLoop::StartEndOrSeekRamps(const ClockReading& r, double t, bool seek, double now_s) {
  const double track_end = track_.samples.empty() ? 0.0 : track_.samples.back().time_s;
  const bool at_end = r.valid && (r.eof || t > track_end);
  if (seek && ending_ && !at_end) ending_ = false;
  if (at_end && !ending_) {
    ending_ = true;
    end_start_s_ = now_s;
    for (int a = 0; a < kNumActuators; ++a) StartRamp(a, now_s, o_.end_ramp_s);
  } else if (seek) {
    for (int a = 0; a < kNumActuators; ++a) StartRamp(a, now_s, o_.seek_ramp_s);
  }
}

TickRecord& HapticLoop::NextRecord(double now_s, double media_s, double gain) {
  TickRecord& rec = ring_[ring_next_];
  ring_next_ = (ring_next_ + 1) % ring_.size();
  if (ring_next_ == 0) ring_wrapped_ = true;
  rec.wall_s = now_s;
  rec.media_s = media_s;
  rec.flags = 0;
  rec.gain = static_cast<float>(gain);
  return rec;
}

// The track's target, raised-cosine blended from where a start, seek or end
// ramp began.
Eigen::Vector3d HapticLoop::RampedGoal(int a, const Eigen::Vector3d& track_m, double now_s) {
  if (ramp_len_s_[a] <= 0) return track_m;
  const double u = (now_s - ramp_start_s_[a]) / ramp_len_s_[a];
  if (u >= 1) {
    ramp_len_s_[a] = 0;
    return track_m;
  }
  const double w = 0.5 - 0.5 * std::cos(M_PI * std::max(0.0, u));
  return ramp_from_m_[a] + w * (track_m - ramp_from_m_[a]);
}

bool HapticLoop::DriveActuator(int a, const Eigen::Vector3d& track_m, double now_s, double gain,
                               TickRecord* rec, bool* homed) {
  Device* dev = seat_.devices[a].get();
  if (!dev) return true;
  ActuatorSafety& safe = safety_[a];
  safe.ClearTickFaults();
  DeviceState& s = state_[a];
  if (!started_[a] && s.homed) {
    // First homed tick: start where the grip is, ramp to the track.
    started_[a] = true;
    safe.ResetTarget(s.pos_m);
    target_m_[a] = s.pos_m;
    StartRamp(a, now_s, o_.start_ramp_s);
  }
  const Eigen::Vector3d goal = RampedGoal(a, track_m, now_s);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  if (s.homed && started_[a]) {
    target_m_[a] = safe.FilterTarget(goal);
    force = o_.k_n_m * (target_m_[a] - s.pos_m) - o_.d_n_s_m * s.vel_m_s;  // Eq. 7
  }
  force_n_[a] = safe.FilterForce(force, gain);
  s = dev->Exchange(force_n_[a]);
  rec->flags |= safe.tick_faults();
  for (int k = 0; k < 3; ++k) {
    rec->target_m[a][k] = static_cast<float>(target_m_[a][k]);
    rec->pos_m[a][k] = static_cast<float>(s.pos_m[k]);
    rec->force_n[a][k] = static_cast<float>(force_n_[a][k]);
  }
  if (s.fault != DeviceFault::kNone) return false;
  *homed = *homed && s.homed;
  return true;
}

void HapticLoop::RecordSync(const ClockReading& r, double t, double now_s) {
  if (!r.valid || r.paused || ending_) return;
  const double after = now_fn_ ? now_fn_() : now_s;
  double truth = 0;
  if (clock_.TrueMediaTime(after, &truth)) stats_.sync_error.Add(truth - t);
  if (now_fn_) stats_.tick_work.Add(after - now_s);
}

bool HapticLoop::Tick(double now_s) {
  if (status_ != LoopStatus::kRunning) {
    ZeroAll();
    return false;
  }
  try {
    const double dt = RecordTiming(now_s);
    if (!std::isfinite(now_s)) return Fail("non-finite wall time");
    if (o_.stop_on_request && StopRequested()) {
      ZeroAll();
      status_ = LoopStatus::kStopped;
      return false;
    }
    ClockReading r;
    const bool seek = ReadClockSeek(&r);
    if (r.finished) {
      ZeroAll();
      status_ = LoopStatus::kFinished;
      return false;
    }
    const bool stalled =
        r.valid && !r.paused && !r.eof && now_s - r.wall_s > o_.safety.clock_stall_s;
    const bool late = dt > o_.safety.max_tick_gap_s;
    const int trips_before = watchdog_.trips();
    const double gain = watchdog_.Update(dt, !stalled && !late);
    stats_.watchdog_trips += watchdog_.trips() - trips_before;

    const double t = Extrapolate(r, now_s);
    last_media_s_.store(t, std::memory_order_relaxed);
    StartEndOrSeekRamps(r, t, seek, now_s);
    Eigen::Vector3d raw[kNumActuators];
    if (r.valid && !ending_) {
      track_.Sample(t, raw, &hint_);
    } else {
      for (auto& v : raw) v.setZero();  // centre
    }
    TickRecord& rec = NextRecord(now_s, t, gain);
    bool all_homed = true;
    for (int a = 0; a < kNumActuators; ++a) {
      if (!DriveActuator(a, raw[a], now_s, gain, &rec, &all_homed))
        return Fail(DeviceFaultName(state_[a].fault));
    }
    all_homed_.store(all_homed, std::memory_order_relaxed);
    RecordSync(r, t, now_s);
    // Back at the centre and the film is over (a track shorter than the
    // film holds the centre until the film ends): stop.
    if (ending_ && o_.finish_at_end && r.eof && now_s - end_start_s_ >= o_.end_ramp_s) {
      ZeroAll();
      status_ = LoopStatus::kFinished;
      return false;
    }
    return true;
  } catch (...) {
    ZeroAll();
    status_ = LoopStatus::kFaulted;
    fault_ = "exception in the haptic tick";
    throw;
  }
}

void HapticLoop::DumpRecent(std::ostream& out) const {
  out << "wall_s,media_s,gain,flags";
  for (int a = 0; a < kNumActuators; ++a) {
    const std::string n = ActuatorName(static_cast<Actuator>(a));
    for (const char* q : {"target", "pos", "force"})
      for (const char* x : {"x", "y", "z"}) out << ',' << n << '_' << q << '_' << x;
  }
  out << '\n';
  const size_t n = ring_wrapped_ ? ring_.size() : ring_next_;
  const size_t start = ring_wrapped_ ? ring_next_ : 0;
  for (size_t i = 0; i < n; ++i) {
    const TickRecord& r = ring_[(start + i) % ring_.size()];
    out << r.wall_s << ',' << r.media_s << ',' << r.gain << ',' << r.flags;
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) out << ',' << r.target_m[a][k];
      for (int k = 0; k < 3; ++k) out << ',' << r.pos_m[a][k];
      for (int k = 0; k < 3; ++k) out << ',' << r.force_n[a][k];
    }
    out << '\n';
  }
}

}  // namespace hapcine
