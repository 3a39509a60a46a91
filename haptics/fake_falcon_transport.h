#pragma once
// A Novint Falcon in software, behind the UsbTransport seam: it plays the FTDI
// bridge (status bytes, baud/DTR state, purges) and the Falcon (bootloader
// handshake, firmware echo, normal-mode packets, homing) byte for byte as
// described in novint-falcon.md, so the firmware loader and FalconDevice are
// tested without hardware. Its knobs inject the failures seen in the field.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "haptics/falcon_kinematics.h"
#include "haptics/falcon_protocol.h"
#include "haptics/usb_transport.h"

namespace hapcine {

class FakeFalconTransport : public UsbTransport {
 public:
  // kDead: a wrong image was loaded; the device ignores everything.
  enum class Mode { kBootloader, kAwaitA, kLoading, kLoaded, kRunning, kDead };

  // `expected_firmware`: the image the fake accepts; a different image loads
  // "successfully" byte by byte but never boots (as with a wrong file).
  explicit FakeFalconTransport(std::vector<uint8_t> expected_firmware);

  // --- failure injection ---
  int ignore_handshakes = 0;        // first N handshakes get no answer
  int corrupt_echo_attempts = 0;    // first N loads echo one wrong byte
  int homing_packets_needed = 5;    // homing packets until all axes home
  bool unplugged = false;           // every transfer fails
  bool firmware_preloaded = false;  // start in normal mode (firmware running)
  bool mute = false;                // running, but sends no replies

  // --- the simulated grip ---
  Eigen::Vector3d falcon_pos_m = FalconCentre();  // Falcon frame
  uint8_t buttons = 0;

  // --- what the host did ---
  Mode mode() const { return mode_; }
  int handshakes_seen() const { return handshakes_; }
  int load_attempts() const { return load_attempts_; }
  const FalconCommand& last_command() const { return last_command_; }
  int commands_seen() const { return commands_; }
  uint16_t baud_divisor() const { return baud_; }
  uint16_t latency_ms() const { return latency_; }

  bool Control(uint8_t request, uint16_t value) override;
  int BulkWrite(const uint8_t* data, int n, int timeout_ms) override;
  int BulkRead(uint8_t* buf, int capacity, int timeout_ms) override;
  std::string Describe() const override { return "fake Falcon"; }

 private:
  void Queue(const uint8_t* data, size_t n) { pending_.insert(pending_.end(), data, data + n); }
  void OnCommandByte(uint8_t b);

  std::vector<uint8_t> firmware_;
  FalconKinematics kin_;
  Mode mode_ = Mode::kBootloader;
  bool dtr_ = false;
  uint16_t baud_ = 0;
  uint16_t latency_ = 16;
  int handshakes_ = 0;
  int load_attempts_ = 0;
  size_t loaded_ = 0;
  bool load_ok_ = true;
  uint8_t homed_ = 0;
  int homing_packets_ = 0;
  int commands_ = 0;
  FalconCommand last_command_;
  std::vector<uint8_t> rx_;      // partial command frame from the host
  std::deque<uint8_t> pending_;  // device -> host payload bytes
};

}  // namespace hapcine
