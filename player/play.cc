#include "player/play.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "haptics/device_config.h"
#include "haptics/falcon_firmware.h"
#include "haptics/hjif_import.h"
#include "haptics/safety.h"
#include "haptics/usb_transport.h"
#include "player/loop_runner.h"
#include "player/mpv_clock.h"

namespace hapcine {
namespace fs = std::filesystem;

void PlayOptions::Check() const {
  if (device != "falcon" && device != "sim" && device != "none")
    throw UsageError("--device must be falcon, sim or none (got '" + device + "')");
  if (video.empty() && !wall_clock) throw UsageError("give VIDEO (or --no-video with --track)");
  if (wall_clock && video.empty() && track.empty()) throw UsageError("--no-video needs --track");
  if (!(duration_tolerance_s >= 0 && std::isfinite(duration_tolerance_s))) throw UsageError("--duration-tolerance must be >= 0");
  if (!(max_run_s >= 0)) throw UsageError("max_run_s must be >= 0");
  loop.Check();
  sim.Check();
}

std::string ResolveTrackPath(const std::string& video, const std::string& track) {
  if (!track.empty()) {
    if (!fs::exists(track)) throw Error(track, "haptic track not found");
    return track;
  }
  const fs::path v(video);
  const fs::path guess = v.parent_path() / (v.stem().string() + ".haptic.csv");
  if (fs::exists(guess)) return guess.string();
  throw Error(video, "no haptic track given and none beside the video (looked for " +
                         guess.string() + "); make one with `hapcine haptics` or pass --track");
}

namespace {

std::unique_ptr<Device> MakeFalcon(const PlayOptions& o, const std::string& serial,
                                   const Eigen::Matrix3d& mount, double max_force_n,
                                   std::ostream& log) {
  FalconDeviceOptions fo;
  fo.serial = serial;
  fo.firmware_path = o.firmware;
  fo.seat_from_falcon = mount;
  fo.max_force_n = max_force_n;
  fo.firmware = o.firmware_options;
  fo.firmware.cancelled = [] { return StopRequested(); };  // Ctrl-C while loading
  fo.progress = [&log, serial](const std::string& line) {
    log << "falcon " << serial << ": " << line << "\n";
  };
  // Null: FalconDevice::Open() opens it through libusb.
  return std::make_unique<FalconDevice>(o.open_falcon ? o.open_falcon(serial) : nullptr, fo);
}

}  // namespace

HapSeat MakeSeat(const PlayOptions& o, std::ostream& log) {
  HapSeat seat;
  if (o.device == "none") return seat;
  if (o.device == "sim") {
    for (auto& d : seat.devices) d = std::make_unique<SimDevice>(o.sim);
    return seat;
  }
  const std::vector<UsbDeviceInfo> found =
      o.list_falcons ? o.list_falcons() : ListFalconUsbDevices();
  if (!o.seat_config.empty()) {
    const SeatConfig config = ReadSeatConfigFile(o.seat_config);
    for (int a = 0; a < kNumActuators; ++a) {
      if (!config.roles[a]) continue;
      const SeatDeviceConfig& c = *config.roles[a];
      const bool present = std::any_of(
          found.begin(), found.end(), [&](const UsbDeviceInfo& d) { return d.serial == c.serial; });
      if (!present)
        throw Error(o.seat_config, std::string("Falcon for '") +
                                       ActuatorName(static_cast<Actuator>(a)) + "' (serial " +
                                       c.serial + ") is not connected; " +
                                       DescribeFalconUsbDevices(found));
      seat.devices[a] =
          MakeFalcon(o, c.serial, c.seat_from_falcon, c.max_force_n.value_or(9.0), log);
    }
    if (seat.count() == 0) throw Error(o.seat_config, "maps no device to a role");
    return seat;
  }
  std::vector<std::string> serials;
  for (const auto& d : found) {
    if (!d.problem.empty()) throw Error("falcon", DescribeFalconUsbDevices(found));
    serials.push_back(d.serial);
  }
  if (serials.empty()) {
    std::string what = DescribeFalconUsbDevices(found) + " (is it plugged in and powered?)";
    if (!o.list_falcons) what += "; " + DescribeAllUsbDevices();  // the real bus only
    throw Error("falcon", what);
  }
  std::sort(serials.begin(), serials.end());
  // Without a config: 1 Falcon -> head; 2 -> left, right; 3 -> head, left,
  // right in serial order.
  std::vector<int> roles = serials.size() == 1   ? std::vector<int>{0}
                           : serials.size() == 2 ? std::vector<int>{1, 2}
                                                 : std::vector<int>{0, 1, 2};
  for (size_t i = 0; i < roles.size() && i < serials.size(); ++i) {
    seat.devices[roles[i]] = MakeFalcon(o, serials[i], Eigen::Matrix3d::Identity(), 9.0, log);
    log << "falcon serial " << serials[i] << " -> " << ActuatorName(static_cast<Actuator>(roles[i]))
        << " (no --seat-config: assigned in serial order)\n";
  }
  return seat;
}

namespace {

// Checks the track's length against the video's (mpv's duration).
void CheckDuration(const PlayOptions& o, const std::string& track_path, double track_end_s,
                   double video_s, PlayResult* result) {
  if (video_s < 0) {
    result->warnings.push_back("mpv reported no duration; track length not checked");
    return;
  }
  if (std::abs(video_s - track_end_s) <= o.duration_tolerance_s) return;
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "track ends at " << track_end_s
    << " s but the video lasts " << video_s << " s (more than " << o.duration_tolerance_s
    << " s apart): is it the track of this video?"
    << (track_end_s < video_s ? " The actuators return to the centre when the track ends."
                              : " The track is cut at the end of the video.");
  if (o.strict_duration) throw Error(track_path, s.str());
  result->warnings.push_back(s.str());
}

// Opens every device; false when a stop was requested meanwhile.
bool OpenDevices(HapSeat& seat, std::ostream& log) {
  for (auto& d : seat.devices) {
    if (!d) continue;
    log << "opening " << d->Name() << "...\n";
    try {
      d->Open();
    } catch (const Error&) {
      if (StopRequested()) return false;  // e.g. firmware loading cancelled
      throw;
    }
    if (StopRequested()) return false;
  }
  return true;
}

// The clock the loop follows: mpv playing the film, or a wall clock.
struct PlaybackClock {
  std::unique_ptr<MediaClock> clock;
  MpvClock* mpv = nullptr;
  WallClock* wall = nullptr;
  double film_s = 0;  // how long playback lasts
};

PlaybackClock MakePlaybackClock(const PlayOptions& o, const std::string& track_path,
                                double track_end_s, bool start_paused, PlayResult* result) {
  PlaybackClock pc;
  pc.film_s = track_end_s;
  if (o.wall_clock) {
    auto w = std::make_unique<WallClock>(track_end_s, 0.0, start_paused);
    pc.wall = w.get();
    pc.clock = std::move(w);
    if (!o.video.empty())
      result->warnings.push_back(
          "--no-video: the video's duration was not checked against the track");
    return pc;
  }
  MpvOptions mo;
  mo.headless = o.headless;
  mo.fullscreen = o.fullscreen;
  mo.start_paused = start_paused;
  auto m = std::make_unique<MpvClock>(o.video, mo);
  m->WaitLoaded(20.0);
  pc.mpv = m.get();
  pc.clock = std::move(m);
  double video_s = -1;
  for (int i = 0; i < 100 && (video_s = pc.mpv->duration_s()) < 0; ++i) usleep(10000);
  CheckDuration(o, track_path, track_end_s, video_s, result);
  if (video_s > 0) pc.film_s = video_s;
  return pc;
}

// Zeroes and closes, then reads back what each device was last sent: the
// proof that the exit left no force.
void ZeroCloseAndReport(HapSeat& seat, PlayResult* result, std::ostream& log) {
  ZeroAndClose(seat);
  if (seat.count() == 0) return;
  log << "last force sent on exit:";
  for (int a = 0; a < kNumActuators; ++a) {
    if (!seat.devices[a]) continue;
    result->last_sent_force_n[a] = seat.devices[a]->LastSentForceN();
    log << " " << ActuatorName(static_cast<Actuator>(a)) << " " << std::fixed
        << std::setprecision(3) << result->last_sent_force_n[a] << " N";
  }
  log << "\n";
}

// After a fault: the last ticks go to the fault log, then the error is thrown.
[[noreturn]] void ReportFault(const PlayOptions& o, const HapticLoop& loop,
                              const std::exception_ptr& error, std::ostream& log) {
  try {
    AtomicFile f(o.fault_log);
    loop.DumpRecent(f.stream());
    f.Commit();
    log << "last " << 2048 << " ticks written to " << o.fault_log << "\n";
  } catch (const std::exception& e) {
    log << "could not write the fault log: " << e.what() << "\n";
  }
  if (error) std::rethrow_exception(error);
  throw Error("haptic loop", "stopped with zero force: " + loop.fault_message());
}

void LogLoopSummary(const PlayOptions& o, const HapticLoop& loop, std::ostream& log) {
  const LoopStats& st = loop.stats();
  if (o.print_stats) {
    log << st.Summary();
  } else {
    log << "played to " << std::fixed << std::setprecision(2) << loop.last_media_s()
        << " s: " << st.ticks << " ticks, " << st.missed_ticks << " missed (--stats for details)\n";
  }
}

}  // namespace

PlayResult Play(const PlayOptions& o, std::ostream& log) {
  o.Check();
  PlayResult result;
  // Signals first: a Ctrl-C during firmware loading or mpv start-up also
  // ends with zero force (the guard below) instead of killing the process.
  ClearStopRequest();
  InstallStopSignals();
  struct Restore {
    ~Restore() { RestoreStopSignals(); }
  } restore;

  const std::string track_path = ResolveTrackPath(o.video, o.track);
  const HapticTrack track = ReadAnyHapticTrackFile(track_path);  // *.haptic.csv or .hjif
  if (track.samples.empty()) throw Error(track_path, "haptic track has no rows");
  const double track_end_s = track.samples.back().time_s;
  if (!o.video.empty() && !fs::exists(o.video)) throw Error(o.video, "video not found");
  if (o.device == "falcon" && !o.firmware.empty()) ReadFirmwareFile(o.firmware);  // fail early

  HapSeat seat = MakeSeat(o, log);
  ZeroForceGuard guard(seat);  // zero + close on every way out of here
  auto stopped_early = [&] {
    result.status = LoopStatus::kStopped;
    result.stop_signal = StopSignal();
    ZeroAndClose(seat);
    log << "stopped by signal before playback; forces zeroed\n";
    return result;
  };
  if (!OpenDevices(seat, log)) return stopped_early();
  // Falcons must be homed before the film starts: the clock is held paused
  // (the loop already runs, homing, with zero force) until they are.
  const bool wait_for_homing = o.device == "falcon";
  PlaybackClock pc = MakePlaybackClock(o, track_path, track_end_s, wait_for_homing, &result);
  for (const auto& w : result.warnings) log << "warning: " << w << "\n";
  if (StopRequested()) return stopped_early();

  LoopOptions lo = o.loop;
  // In a window the user decides when it ends (q / closing it); headless
  // and wall-clock playback end once the film is over and the actuators are
  // back at the centre.
  lo.finish_at_end = o.headless || o.wall_clock;
  HapticLoop loop(track, seat, *pc.clock, lo);

  RunnerOptions ro;
  ro.realtime = o.realtime;
  ro.max_run_s = o.max_run_s;
  Progress playing(log, isatty(STDERR_FILENO) ? ProgressMode::kBar : ProgressMode::kLines, "playing", "s");
  bool holding = wait_for_homing;
  if (holding) log << "home each Falcon: pull the grip fully out and push it back in "
                      "(red LED -> green); the film starts when all are homed\n";
  auto progress = [&] {
    const double now = SteadySeconds();
    if (holding) {
      if (!loop.all_homed()) return;
      holding = false;
      log << "all Falcons homed: playing\n";
      if (pc.mpv) pc.mpv->SetPause(false);
      if (pc.wall) pc.wall->Start(now);
    }
    playing.Update(loop.last_media_s(), pc.film_s);
  };
  log << "playing " << track_path << " with " << (o.device == "none" ? "no device" : o.device)
      << " (k=" << lo.k_n_m << " N/m, d=" << lo.d_n_s_m << " N s/m)\n";
  const RunReport report = RunLoop(loop, ro, nullptr, progress, 0.1);
  playing.Close();
  result.realtime = report.realtime;
  if (!report.realtime) log << "note: " << report.realtime_note << "\n";
  result.status = loop.status();
  result.stats = loop.stats();
  result.stop_signal = StopSignal();
  if (pc.mpv) pc.mpv->Quit();

  ZeroCloseAndReport(seat, &result, log);  // the guard repeats it harmlessly
  LogLoopSummary(o, loop, log);
  if (loop.status() == LoopStatus::kFaulted || report.error)
    ReportFault(o, loop, report.error, log);
  if (loop.status() == LoopStatus::kStopped) log << "stopped by signal; forces zeroed\n";
  return result;
}

}  // namespace hapcine
