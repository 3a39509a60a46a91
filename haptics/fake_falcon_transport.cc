#include "haptics/fake_falcon_transport.h"

#include <algorithm>
#include <cmath>

namespace hapcine {

FakeFalconTransport::FakeFalconTransport(std::vector<uint8_t> expected_firmware)
    : firmware_(std::move(expected_firmware)) {}

bool FakeFalconTransport::Control(uint8_t request, uint16_t value) {
  if (unplugged) return false;
  if (firmware_preloaded && mode_ == Mode::kBootloader) mode_ = Mode::kRunning;
  switch (request) {
    case ftdi::kReset:
      pending_.clear();
      rx_.clear();
      break;
    case ftdi::kModemControl:
      if (value == ftdi::kDtrHigh) {
        // DTR rising at 9600 baud resets the Falcon into its bootloader.
        if (!dtr_ && baud_ == ftdi::kBaud9600) {
          mode_ = Mode::kBootloader;
          loaded_ = 0;
        }
        dtr_ = true;
      } else if (value == ftdi::kDtrLow) {
        dtr_ = false;
      }
      break;
    case ftdi::kBaudRate:
      baud_ = value;
      // The image boots once the host switches to the normal baud rate.
      if (mode_ == Mode::kLoaded && value == ftdi::kBaudNormal) mode_ = Mode::kRunning;
      break;
    case ftdi::kLatencyTimer:
      latency_ = value;
      break;
    default:
      break;
  }
  return true;
}

int FakeFalconTransport::BulkWrite(const uint8_t* data, int n, int timeout_ms) {
  if (unplugged) return -1;
  if (firmware_preloaded && mode_ == Mode::kBootloader) mode_ = Mode::kRunning;
  switch (mode_) {
    case Mode::kBootloader: {
      static const uint8_t kHello[3] = {0x0A, 0x43, 0x0D};
      static const uint8_t kAnswer[4] = {0x0A, 0x44, 0x2C, 0x0D};
      if (n == 3 && std::equal(data, data + 3, kHello) && dtr_ && baud_ == ftdi::kBaud9600) {
        ++handshakes_;
        if (handshakes_ > ignore_handshakes) {
          Queue(kAnswer, 4);
          mode_ = Mode::kAwaitA;
        }
      }
      break;
    }
    case Mode::kAwaitA:
      if (n >= 1 && data[0] == 'A' && !dtr_ && baud_ == ftdi::kBaudFirmware) {
        Queue(data, 1);
        mode_ = Mode::kLoading;
        loaded_ = 0;
        load_ok_ = true;
        ++load_attempts_;
      }
      break;
    case Mode::kLoading:
      for (int i = 0; i < n; ++i) {
        uint8_t echo = data[i];
        if (load_attempts_ <= corrupt_echo_attempts && loaded_ == 100) echo ^= 0x5A;
        if (loaded_ >= firmware_.size() || firmware_[loaded_] != data[i]) load_ok_ = false;
        Queue(&echo, 1);
        ++loaded_;
      }
      if (loaded_ >= firmware_.size()) mode_ = load_ok_ ? Mode::kLoaded : Mode::kDead;
      break;
    case Mode::kLoaded:
    case Mode::kDead:
      break;
    case Mode::kRunning:
      for (int i = 0; i < n; ++i) OnCommandByte(data[i]);
      break;
  }
  return n;
}

void FakeFalconTransport::OnCommandByte(uint8_t b) {
  if (rx_.empty() && b != '<') return;
  rx_.push_back(b);
  if (rx_.size() < static_cast<size_t>(kFalconPacketSize)) return;
  FalconCommand cmd;
  const bool ok = DecodeCommand(rx_.data(), &cmd);
  rx_.clear();
  if (!ok) return;
  ++commands_;
  last_command_ = cmd;
  if (cmd.homing && homed_ != kFalconAllHomed && ++homing_packets_ >= homing_packets_needed)
    homed_ = kFalconAllHomed;
  FalconReply reply;
  Eigen::Vector3d theta;
  if (kin_.Inverse(falcon_pos_m, &theta)) {
    for (int i = 0; i < 3; ++i)
      reply.encoder[i] = SaturateTorque(std::round(AngleRadToEncoder(theta[i])));
  }
  reply.buttons = buttons;
  reply.homed_axes = homed_;
  uint8_t out[kFalconPacketSize];
  EncodeReply(reply, out);
  if (!mute) Queue(out, kFalconPacketSize);
}

int FakeFalconTransport::BulkRead(uint8_t* buf, int capacity, int timeout_ms) {
  if (unplugged) return -1;
  // The FTDI chip: each 64-byte USB packet starts with 2 status bytes; with
  // nothing to send it still answers with a status-only packet.
  int n = 0;
  do {
    if (n + 2 > capacity) break;
    buf[n++] = 0x31;
    buf[n++] = 0x60;
    int room = std::min(62, capacity - n);
    while (room-- > 0 && !pending_.empty()) {
      buf[n++] = pending_.front();
      pending_.pop_front();
    }
  } while (!pending_.empty() && n % 64 == 0);
  return n;
}

}  // namespace hapcine
