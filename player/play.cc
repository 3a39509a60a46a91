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
#include "haptics/device_config.h"
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
  if (!(duration_tolerance_s >= 0)) throw UsageError("--duration-tolerance must be >= 0");
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
                                   const Eigen::Matrix3d& mount, double max_force_n) {
  FalconDeviceOptions fo;
  fo.serial = serial;
  fo.firmware_path = o.firmware;
  fo.seat_from_falcon = mount;
  fo.max_force_n = max_force_n;
  return std::make_unique<FalconDevice>(nullptr, fo);
}

}  // namespace

HapSeat MakeSeat(const PlayOptions& o, std::ostream& log) {
  HapSeat seat;
  if (o.device == "none") return seat;
  if (o.device == "sim") {
    for (auto& d : seat.devices) d = std::make_unique<SimDevice>(o.sim);
    return seat;
  }
  const std::vector<UsbDeviceInfo> found = ListFalconUsbDevices();
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
      seat.devices[a] = MakeFalcon(o, c.serial, c.seat_from_falcon, c.max_force_n.value_or(9.0));
    }
    if (seat.count() == 0) throw Error(o.seat_config, "maps no device to a role");
    return seat;
  }
  std::vector<std::string> serials;
  for (const auto& d : found) {
    if (!d.problem.empty()) throw Error("falcon", DescribeFalconUsbDevices(found));
    serials.push_back(d.serial);
  }
  if (serials.empty())
    throw Error("falcon", DescribeFalconUsbDevices(found) + " (is it plugged in and powered?)");
  std::sort(serials.begin(), serials.end());
  // Without a config: 1 Falcon -> head; 2 -> left, right; 3 -> head, left,
  // right in serial order.
  std::vector<int> roles = serials.size() == 1   ? std::vector<int>{0}
                           : serials.size() == 2 ? std::vector<int>{1, 2}
                                                 : std::vector<int>{0, 1, 2};
  for (size_t i = 0; i < roles.size() && i < serials.size(); ++i) {
    seat.devices[roles[i]] = MakeFalcon(o, serials[i], Eigen::Matrix3d::Identity(), 9.0);
    log << "falcon serial " << serials[i] << " -> " << ActuatorName(static_cast<Actuator>(roles[i]))
        << " (no --seat-config: assigned in serial order)\n";
  }
  return seat;
}

PlayResult Play(const PlayOptions& o, std::ostream& log) {
  o.Check();
  PlayResult result;
  const std::string track_path = ResolveTrackPath(o.video, o.track);
  const HapticTrack track = ReadHapticTrackFile(track_path);
  if (track.samples.empty()) throw Error(track_path, "haptic track has no rows");
  const double track_end_s = track.samples.back().time_s;
  if (!o.video.empty() && !fs::exists(o.video)) throw Error(o.video, "video not found");

  HapSeat seat = MakeSeat(o, log);
  ZeroForceGuard guard(seat);  // zero + close on every way out of here
  for (auto& d : seat.devices) {
    if (!d) continue;
    log << "opening " << d->Name() << "...\n";
    d->Open();
  }
  if (o.device == "falcon")
    log << "home each Falcon: pull the grip fully out and push it back in (red LED -> green)\n";

  std::unique_ptr<MediaClock> clock;
  MpvClock* mpv = nullptr;
  if (o.wall_clock) {
    clock = std::make_unique<WallClock>(track_end_s);
    if (!o.video.empty())
      result.warnings.push_back(
          "--no-video: the video's duration was not checked against the track");
  } else {
    MpvOptions mo;
    mo.headless = o.headless;
    mo.fullscreen = o.fullscreen;
    auto m = std::make_unique<MpvClock>(o.video, mo);
    m->WaitLoaded(20.0);
    mpv = m.get();
    clock = std::move(m);
    double video_s = -1;
    for (int i = 0; i < 100 && (video_s = mpv->duration_s()) < 0; ++i) usleep(10000);
    if (video_s >= 0 && std::abs(video_s - track_end_s) > o.duration_tolerance_s) {
      std::ostringstream s;
      s << std::fixed << std::setprecision(2) << "track ends at " << track_end_s
        << " s but the video lasts " << video_s << " s (more than " << o.duration_tolerance_s
        << " s apart): is it the track of this video?";
      if (o.strict_duration) throw Error(track_path, s.str());
      result.warnings.push_back(s.str());
    } else if (video_s < 0) {
      result.warnings.push_back("mpv reported no duration; track length not checked");
    }
  }
  for (const auto& w : result.warnings) log << "warning: " << w << "\n";

  LoopOptions lo = o.loop;
  // In a window the user decides when it ends (q / closing it); headless
  // and wall-clock playback end once the actuators are back at the centre.
  lo.finish_at_end = o.headless || o.wall_clock;
  HapticLoop loop(track, seat, *clock, lo);

  ClearStopRequest();
  InstallStopSignals();
  struct Restore {
    ~Restore() { RestoreStopSignals(); }
  } restore;
  RunnerOptions ro;
  ro.realtime = o.realtime;
  ro.max_run_s = o.max_run_s;
  const bool tty = isatty(STDERR_FILENO);
  double last_print = -1e9;
  auto progress = [&] {
    const double t = loop.last_media_s();
    const double now = SteadySeconds();
    if (tty) {
      log << "\rplaying " << std::fixed << std::setprecision(1) << t << " / " << track_end_s << " s"
          << std::flush;
    } else if (now - last_print >= 10) {
      log << "playing " << std::fixed << std::setprecision(1) << t << " / " << track_end_s
          << " s\n";
      last_print = now;
    }
  };
  log << "playing " << track_path << " with " << (o.device == "none" ? "no device" : o.device)
      << " (k=" << lo.k_n_m << " N/m, d=" << lo.d_n_s_m << " N s/m)\n";
  const RunReport report = RunLoop(loop, ro, nullptr, progress);
  if (tty) log << "\n";
  result.realtime = report.realtime;
  if (!report.realtime) log << "note: " << report.realtime_note << "\n";
  result.status = loop.status();
  result.stats = loop.stats();
  if (mpv) mpv->Quit();

  const LoopStats& st = loop.stats();
  if (o.print_stats) {
    log << st.Summary();
  } else {
    log << "played to " << std::fixed << std::setprecision(2) << loop.last_media_s()
        << " s: " << st.ticks << " ticks, " << st.missed_ticks << " missed (--stats for details)\n";
  }
  if (loop.status() == LoopStatus::kFaulted || report.error) {
    try {
      AtomicFile f(o.fault_log);
      loop.DumpRecent(f.stream());
      f.Commit();
      log << "last " << 2048 << " ticks written to " << o.fault_log << "\n";
    } catch (const std::exception& e) {
      log << "could not write the fault log: " << e.what() << "\n";
    }
    if (report.error) std::rethrow_exception(report.error);
    throw Error("haptic loop", "stopped with zero force: " + loop.fault_message());
  }
  if (loop.status() == LoopStatus::kStopped) log << "stopped by signal; forces zeroed\n";
  return result;
}

}  // namespace hapcine
