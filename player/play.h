#pragma once
// `hapcine play`: a film with its haptic track on the HapSeat. The library
// function behind cli/cmd_play.cc.
//
// Flow: resolve and read the track (default: <video stem>.haptic.csv beside
// the video), build and open the seat (falcon: libusb + firmware; sim;
// none), start the media clock (mpv window, mpv headless, or the wall
// clock; with Falcons it is held paused until every Falcon is homed), check
// the track against the video's duration, run the 1 kHz loop until the film
// ends (headless/wall clock: after returning to the centre) or the window is
// closed / Ctrl-C / SIGTERM, zero and close the seat, report the last force
// each device was sent, and print the loop statistics.
// Zero force on every exit path: ZeroForceGuard + the loop's own zeroing;
// SIGINT/SIGTERM are caught from the start (also during firmware loading).

#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "haptics/device.h"
#include "haptics/falcon_device.h"
#include "haptics/sim_device.h"
#include "haptics/usb_transport.h"
#include "player/haptic_loop.h"

namespace hapcine {

struct PlayOptions {
  std::string video;                            // the film (required unless wall_clock)
  std::string track;                            // *.haptic.csv; empty: <video stem>.haptic.csv
  std::string device = "sim";                   // falcon | sim | none
  bool headless = false;                        // mpv without window or sound (vo/ao=null)
  bool wall_clock = false;                      // no mpv at all: media time = wall time
  bool fullscreen = false;                      // start mpv full screen
  std::string firmware;                         // Falcon firmware image (the user's copy)
  std::string seat_config;                      // JSON serial -> role map (device_config.h)
  bool print_stats = false;                     // full loop statistics at the end
  double duration_tolerance_s = 1.0;            // track vs video length mismatch allowed
  bool strict_duration = false;                 // a mismatch is an error instead of a warning
  bool realtime = true;                         // try SCHED_FIFO for the loop thread
  double max_run_s = 0;                         // > 0: stop after this long (tests)
  std::string fault_log = "hapcine-fault.csv";  // ring buffer dump on a fault
  LoopOptions loop;
  SimDeviceOptions sim;
  FirmwareOptions firmware_options;
  // Tests replace libusb here (a FakeFalconTransport per serial); empty:
  // ListFalconUsbDevices / OpenLibusbTransport.
  std::function<std::vector<UsbDeviceInfo>()> list_falcons;
  std::function<std::unique_ptr<UsbTransport>(const std::string& serial)> open_falcon;
  void Check() const;  // throws UsageError
};

struct PlayResult {
  LoopStatus status = LoopStatus::kRunning;
  LoopStats stats;
  std::vector<std::string> warnings;
  bool realtime = false;
  int stop_signal = 0;  // SIGINT/SIGTERM when stopped by one
  // |F| of the last force each device was sent (after the final zeroing);
  // -1 where the seat has no device.
  std::array<double, kNumActuators> last_sent_force_n{-1, -1, -1};
};

// `<dir>/<stem>.haptic.csv` for `video`, or `track` if given. Throws Error
// naming the path it looked for when neither exists.
std::string ResolveTrackPath(const std::string& video, const std::string& track);

// Builds the seat for `options.device` (not opened). Throws Error: for
// falcon, with the list of 0403:cb48 devices actually found.
HapSeat MakeSeat(const PlayOptions& options, std::ostream& log);

// Plays; progress and statistics go to `log`. Throws hapcine::Error on bad
// input, a device fault (after writing options.fault_log), or mpv failure.
PlayResult Play(const PlayOptions& options, std::ostream& log);

}  // namespace hapcine
