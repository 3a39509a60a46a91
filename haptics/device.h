#pragma once
// One actuator of the HapSeat behind one small interface: a Novint Falcon on
// USB (falcon_device.h) or its simulation (sim_device.h).
//
// Frames and units. Every Device speaks the seat frame of haptic-track.md
// (+X right, +Y up, +Z backward), metres, relative to the centre of ITS OWN
// workspace, so that the track's G'_A and the device's P_A are directly
// comparable in Equation 7. A FalconDevice converts to and from the Falcon's
// own frame (its mounting is part of device_config.h).
//
// The 1 kHz loop calls Exchange() once per tick: it sends a force and returns
// the state measured by that exchange. Exchange() must not allocate, log or
// block for more than a fraction of a millisecond, and should not throw: a
// failing device reports `fault` and the loop stops with zero force. (If one
// throws anyway, the loop commands zero force everywhere and rethrows.)

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "core/haptic_track.h"

namespace hapcine {

enum class DeviceFault : uint8_t {
  kNone = 0,
  kTransferError,  // a USB transfer failed (unplugged, I/O error)
  kNoData,         // the device stopped answering
  kNotOpen,        // Exchange() before Open() or after Close()
};
const char* DeviceFaultName(DeviceFault f);

struct DeviceState {
  Eigen::Vector3d pos_m = Eigen::Vector3d::Zero();    // seat frame, from workspace centre
  Eigen::Vector3d vel_m_s = Eigen::Vector3d::Zero();  // seat frame
  uint8_t buttons = 0;  // bit 0 right, 1 forward, 2 centre, 3 left (Falcon grip)
  bool homed = false;   // position is meaningful; position forces allowed
  DeviceFault fault = DeviceFault::kNone;
};

enum class Led : uint8_t { kGreen = 2, kBlue = 4, kRed = 8 };  // bit masks

class Device {
 public:
  virtual ~Device() = default;
  // Opens the device (may take seconds: firmware). Throws hapcine::Error.
  virtual void Open() = 0;
  // Sends zero force and releases the device. Never throws; safe to repeat.
  virtual void Close() noexcept = 0;
  // Sends `force_n` (seat frame, newtons) and returns the measured state.
  // Real-time safe: no allocation; errors are reported in `fault`.
  virtual DeviceState Exchange(const Eigen::Vector3d& force_n) = 0;
  // Sets the LED mask (bit-or of Led values); applied with the next Exchange.
  virtual void SetLeds(uint8_t mask) noexcept { (void)mask; }
  // Hardware limit on the force this device can render, newtons.
  virtual double MaxForceN() const = 0;
  // Human-readable identity ("sim", "falcon serial A1234").
  virtual std::string Name() const = 0;
  // |F| of the last force actually sent to the device (after the device's own
  // checks: a Falcon sends none before homing), newtons. Lets the player
  // report, on every exit, that the last command really was zero.
  virtual double LastSentForceN() const = 0;
};

// The HapSeat: one optional device per actuator, indexed by Actuator
// (head, left hand, right hand). A missing actuator (nullptr) is skipped.
struct HapSeat {
  std::array<std::unique_ptr<Device>, kNumActuators> devices;
  int count() const {
    int n = 0;
    for (const auto& d : devices) n += d != nullptr;
    return n;
  }
};

// Sends zero force to every device of the seat a few times and closes them.
// Never throws. Used on every exit path (see safety.h ZeroForceGuard).
void ZeroAndClose(HapSeat& seat) noexcept;

}  // namespace hapcine
