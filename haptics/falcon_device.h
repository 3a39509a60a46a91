#pragma once
// A Novint Falcon as one HapSeat actuator, over a UsbTransport (libusb for
// real, FakeFalconTransport in tests).
//
// Open(): opens the USB device (by FTDI serial), loads the firmware if it is
// not already running (from the user's file; retried), enters normal mode.
// Exchange(): one 16-byte command out (torques, homing bit, LEDs), the newest
// 16-byte reply in (encoders, buttons, homed axes). Until all three axes are
// homed the homing bit stays set and no force is sent (the user pulls the
// grip out and pushes it back in); the red LED shows "not homed", green
// "ready". Positions: encoders -> arm angles -> forward kinematics (warm
// started), then into the seat frame with the mounting rotation and relative
// to the workspace centre. Forces: seat -> Falcon frame, tau = J^T F, then
// command counts = counts_per_nm * tau, saturated to +-32767.

#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "haptics/device.h"
#include "haptics/falcon_firmware.h"
#include "haptics/falcon_kinematics.h"
#include "haptics/falcon_protocol.h"
#include "haptics/usb_transport.h"

namespace hapcine {

struct FalconDeviceOptions {
  std::string serial;         // FTDI serial; empty: the only Falcon present
  std::string firmware_path;  // the user's copy of Novint's image
  Eigen::Matrix3d seat_from_falcon = Eigen::Matrix3d::Identity();  // mounting
  double max_force_n = 9.0;  // hardware limit reported to the safety layer
  // Torque command counts per N m of arm torque. The sign and scale follow
  // the reference driver (-10000); not yet calibrated on hardware here.
  double counts_per_nm = -10000.0;
  int read_timeout_ms = 1;         // per-tick wait for a reply (1 ms latency timer)
  int max_silent_ticks = 100;      // no reply for this many ticks -> kNoData
  double velocity_cutoff_hz = 60;  // low-pass on the differentiated position
  FirmwareOptions firmware;
  // Optional: one line per failed firmware attempt (the user sees retries).
  std::function<void(const std::string&)> progress;
  void Check() const;  // throws UsageError
};

class FalconDevice : public Device {
 public:
  // `transport` may be null: Open() then opens the Falcon through libusb.
  FalconDevice(std::unique_ptr<UsbTransport> transport, FalconDeviceOptions options);
  ~FalconDevice() override { Close(); }

  void Open() override;
  void Close() noexcept override;
  DeviceState Exchange(const Eigen::Vector3d& force_n) override;
  void SetLeds(uint8_t mask) noexcept override { user_leds_ = mask; }
  double MaxForceN() const override { return options_.max_force_n; }
  std::string Name() const override;
  double LastSentForceN() const override { return last_sent_force_n_; }

  // Number of firmware attempts Open() needed (0: firmware was running).
  int firmware_attempts() const { return firmware_attempts_; }
  const FalconReply& last_reply() const { return last_reply_; }
  const Eigen::Vector3d& last_torque_counts() const { return last_counts_; }

 private:
  std::unique_ptr<UsbTransport> usb_;
  FalconDeviceOptions options_;
  FalconKinematics kin_;
  FalconPacketParser parser_;
  bool open_ = false;
  uint8_t user_leds_ = 0;
  int firmware_attempts_ = 0;
  int silent_ticks_ = 0;
  bool have_reply_ = false;
  FalconReply last_reply_;
  Eigen::Vector3d falcon_pos_m_ = FalconCentre();
  Eigen::Vector3d falcon_vel_m_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_counts_ = Eigen::Vector3d::Zero();
  double last_sent_force_n_ = 0;  // |F| encoded in the last packet written
  std::chrono::steady_clock::time_point last_reply_time_;
  DeviceState state_;
};

}  // namespace hapcine
