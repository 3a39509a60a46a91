#include "haptics/falcon_device.h"

#include <cmath>

#include "core/error.h"

namespace hapcine {

void FalconDeviceOptions::Check() const {
  if (!(max_force_n > 0 && max_force_n <= 9))
    throw UsageError("Falcon max_force_n must be in (0, 9] N");
  if (!std::isfinite(counts_per_nm) || counts_per_nm == 0)
    throw UsageError("Falcon counts_per_nm must be non-zero");
  if (read_timeout_ms < 1 || read_timeout_ms > 100)
    throw UsageError("Falcon read_timeout_ms must be in [1, 100]");
  if (max_silent_ticks < 1) throw UsageError("Falcon max_silent_ticks must be >= 1");
  if (!(velocity_cutoff_hz > 0)) throw UsageError("Falcon velocity_cutoff_hz must be > 0");
  const double ortho =
      (seat_from_falcon * seat_from_falcon.transpose() - Eigen::Matrix3d::Identity()).norm();
  if (!(ortho < 1e-6)) throw UsageError("Falcon seat_from_falcon must be a rotation");
  firmware.Check();
}

FalconDevice::FalconDevice(std::unique_ptr<UsbTransport> transport, FalconDeviceOptions options)
    : usb_(std::move(transport)), options_(std::move(options)) {
  options_.Check();
}

std::string FalconDevice::Name() const {
  return "falcon" + (options_.serial.empty() ? std::string() : " serial " + options_.serial);
}

void FalconDevice::Open() {
  if (open_) return;
  if (!usb_) usb_ = OpenLibusbTransport(options_.serial);
  // Firmware may survive from an earlier run (the Falcon stays powered).
  firmware_attempts_ = 0;
  if (!(SetFalconNormalMode(*usb_) && FalconFirmwareRunning(*usb_))) {
    const std::vector<uint8_t> image = ReadFirmwareFile(options_.firmware_path);
    firmware_attempts_ = LoadFalconFirmware(*usb_, image, options_.firmware, options_.progress);
  }
  parser_.Clear();
  have_reply_ = false;
  silent_ticks_ = 0;
  state_ = DeviceState();
  open_ = true;
}

void FalconDevice::Close() noexcept {
  if (!open_ || !usb_) return;
  // Zero torque, homing bit set (no position control), LEDs off.
  FalconCommand zero;
  uint8_t out[kFalconPacketSize];
  EncodeCommand(zero, out);
  for (int i = 0; i < 3; ++i)
    if (usb_->BulkWrite(out, kFalconPacketSize, 50) == kFalconPacketSize) last_sent_force_n_ = 0;
  open_ = false;
}

DeviceState FalconDevice::Exchange(const Eigen::Vector3d& force_n) {
  if (!open_) {
    state_.fault = DeviceFault::kNotOpen;
    return state_;
  }
  FalconCommand cmd;
  const bool homed = have_reply_ && last_reply_.homed_axes == kFalconAllHomed;
  cmd.homing = !homed;
  cmd.leds = (user_leds_ & 0x0E) | static_cast<uint8_t>(homed ? Led::kGreen : Led::kRed);
  Eigen::Vector3d counts = Eigen::Vector3d::Zero();
  double sent_n = 0;
  if (homed && force_n.allFinite()) {
    const Eigen::Vector3d falcon_force = options_.seat_from_falcon.transpose() * force_n;
    Eigen::Vector3d tau;
    if (kin_.ForceToTorque(falcon_pos_m_, falcon_force, &tau))
      sent_n = force_n.norm() * TorqueCounts(tau, options_.counts_per_nm, &counts);
  }
  for (int i = 0; i < 3; ++i) {
    cmd.torque[i] = SaturateTorque(counts[i]);
    last_counts_[i] = cmd.torque[i];
  }
  uint8_t out[kFalconPacketSize];
  EncodeCommand(cmd, out);
  if (usb_->BulkWrite(out, kFalconPacketSize, 10) != kFalconPacketSize) {
    state_.fault = DeviceFault::kTransferError;
    return state_;
  }
  last_sent_force_n_ = sent_n;
  uint8_t raw[64], payload[64];
  const int r = usb_->BulkRead(raw, sizeof(raw), options_.read_timeout_ms);
  if (r < 0) {
    state_.fault = DeviceFault::kTransferError;
    return state_;
  }
  parser_.Push(payload, StripFtdiStatus(raw, static_cast<size_t>(r), payload));
  FalconReply reply;
  bool fresh = false;
  while (parser_.Next(&reply)) fresh = true;  // keep the newest
  if (!fresh) {
    if (++silent_ticks_ >= options_.max_silent_ticks) state_.fault = DeviceFault::kNoData;
    return state_;
  }
  silent_ticks_ = 0;
  const auto now = std::chrono::steady_clock::now();
  Eigen::Vector3d theta;
  for (int i = 0; i < 3; ++i) theta[i] = EncoderToAngleRad(reply.encoder[i]);
  Eigen::Vector3d p;
  if (kin_.Forward(theta, falcon_pos_m_, &p) && p.allFinite()) {
    if (have_reply_) {
      const double dt = std::chrono::duration<double>(now - last_reply_time_).count();
      if (dt > 1e-5 && dt < 0.1) {
        const Eigen::Vector3d raw_vel = (p - falcon_pos_m_) / dt;
        const double alpha = 1.0 - std::exp(-2 * M_PI * options_.velocity_cutoff_hz * dt);
        falcon_vel_m_s_ += alpha * (raw_vel - falcon_vel_m_s_);
      }
    }
    falcon_pos_m_ = p;
  }
  last_reply_time_ = now;
  last_reply_ = reply;
  have_reply_ = true;
  state_.pos_m = options_.seat_from_falcon * (falcon_pos_m_ - FalconCentre());
  state_.vel_m_s = options_.seat_from_falcon * falcon_vel_m_s_;
  state_.buttons = reply.buttons;
  state_.homed = reply.homed_axes == kFalconAllHomed;
  state_.fault = DeviceFault::kNone;
  return state_;
}

}  // namespace hapcine
