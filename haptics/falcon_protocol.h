#pragma once
// The Falcon's normal-mode packet protocol (firmware running), bytes only: no
// USB here, so it is tested against hand-computed byte strings.
//
// Both directions use 16-byte frames: '<', 14 payload bytes, '>'. Payload
// bytes 1..12 carry three signed 16-bit words as nibbles, least significant
// nibble first, each byte = nibble + 0x41 ('A'..'P').
//   host -> device: words = motor torque commands; byte 13 = 0x41 + flags
//                   (bit 0 homing mode, bit 1 green, bit 2 blue, bit 3 red
//                   LED); byte 14 = 0x41.
//   device -> host: words = encoder counts; from b = byte 13 - 0x41:
//                   buttons = b & 0x0F (1 right, 2 forward, 4 centre,
//                   8 left), homed axes = (b >> 4) & 7; byte 14 unused.
// The IN endpoint of the FTDI bridge prefixes every 64-byte USB packet with
// 2 modem-status bytes (StripFtdiStatus removes them), and replies may arrive
// split over reads: FalconPacketParser re-frames the byte stream.

#include <cstddef>
#include <cstdint>

namespace hapcine {

constexpr int kFalconPacketSize = 16;
constexpr uint8_t kFalconHomingBit = 0x01;
constexpr uint8_t kFalconAllHomed = 0x07;

struct FalconCommand {
  int16_t torque[3] = {0, 0, 0};
  bool homing = false;
  uint8_t leds = 0;  // bit 1 green, bit 2 blue, bit 3 red (Led in device.h)
};

struct FalconReply {
  int16_t encoder[3] = {0, 0, 0};
  uint8_t buttons = 0;     // 4 bits
  uint8_t homed_axes = 0;  // 3 bits, one per axis
};

// Rounds and saturates to +-32767 (the firmware wraps at 16 bits, so an
// unsaturated 40000 would become a large force the other way). NaN -> 0.
int16_t SaturateTorque(double counts);

void EncodeCommand(const FalconCommand& cmd, uint8_t out[kFalconPacketSize]);
void EncodeReply(const FalconReply& reply, uint8_t out[kFalconPacketSize]);
// False if the frame or a nibble byte is malformed.
bool DecodeCommand(const uint8_t in[kFalconPacketSize], FalconCommand* cmd);
bool DecodeReply(const uint8_t in[kFalconPacketSize], FalconReply* reply);

// Copies the payload of raw FTDI IN data to `out`, dropping the 2 status
// bytes at the start of every `usb_packet_size`-byte USB packet. Returns the
// number of payload bytes. `out` needs room for n bytes.
size_t StripFtdiStatus(const uint8_t* raw, size_t n, uint8_t* out, size_t usb_packet_size = 64);

// Re-frames a byte stream into replies. Fixed buffer: allocation-free.
class FalconPacketParser {
 public:
  // Appends bytes (oldest are dropped if the buffer overflows).
  void Push(const uint8_t* data, size_t n);
  // Extracts the next complete, valid reply; skips garbage up to the next '<'.
  bool Next(FalconReply* reply);
  void Clear() { size_ = 0; }
  size_t garbage_bytes() const { return garbage_; }

 private:
  static constexpr size_t kCapacity = 256;
  uint8_t buf_[kCapacity];
  size_t size_ = 0;
  size_t garbage_ = 0;
};

}  // namespace hapcine
