#include "haptics/falcon_protocol.h"

#include <cmath>
#include <cstring>

namespace hapcine {
namespace {

constexpr uint8_t kNibbleBase = 0x41;

void PutWord(int16_t v, uint8_t* out) {
  const uint16_t u = static_cast<uint16_t>(v);
  for (int k = 0; k < 4; ++k) out[k] = static_cast<uint8_t>(kNibbleBase + ((u >> (4 * k)) & 0xF));
}

bool GetWord(const uint8_t* in, int16_t* v) {
  uint16_t u = 0;
  for (int k = 0; k < 4; ++k) {
    if (in[k] < kNibbleBase || in[k] > kNibbleBase + 0xF) return false;
    u = static_cast<uint16_t>(u | ((in[k] - kNibbleBase) << (4 * k)));
  }
  *v = static_cast<int16_t>(u);
  return true;
}

bool Framed(const uint8_t* in) { return in[0] == '<' && in[kFalconPacketSize - 1] == '>'; }

}  // namespace

int16_t SaturateTorque(double counts) {
  if (!std::isfinite(counts)) return counts > 0 ? 32767 : (counts < 0 ? -32767 : 0);
  if (counts >= 32767) return 32767;
  if (counts <= -32767) return -32767;
  return static_cast<int16_t>(std::lround(counts));
}

void EncodeCommand(const FalconCommand& cmd, uint8_t out[kFalconPacketSize]) {
  out[0] = '<';
  for (int i = 0; i < 3; ++i) PutWord(cmd.torque[i], out + 1 + 4 * i);
  out[13] =
      static_cast<uint8_t>(kNibbleBase + ((cmd.homing ? kFalconHomingBit : 0) | (cmd.leds & 0x0E)));
  out[14] = kNibbleBase;
  out[15] = '>';
}

void EncodeReply(const FalconReply& reply, uint8_t out[kFalconPacketSize]) {
  out[0] = '<';
  for (int i = 0; i < 3; ++i) PutWord(reply.encoder[i], out + 1 + 4 * i);
  out[13] =
      static_cast<uint8_t>(kNibbleBase + ((reply.buttons & 0x0F) | ((reply.homed_axes & 7) << 4)));
  out[14] = kNibbleBase;
  out[15] = '>';
}

bool DecodeCommand(const uint8_t in[kFalconPacketSize], FalconCommand* cmd) {
  if (!Framed(in)) return false;
  FalconCommand c;
  for (int i = 0; i < 3; ++i)
    if (!GetWord(in + 1 + 4 * i, &c.torque[i])) return false;
  if (in[13] < kNibbleBase || in[13] > kNibbleBase + 0xF) return false;
  const uint8_t b = in[13] - kNibbleBase;
  c.homing = (b & kFalconHomingBit) != 0;
  c.leds = b & 0x0E;
  *cmd = c;
  return true;
}

bool DecodeReply(const uint8_t in[kFalconPacketSize], FalconReply* reply) {
  if (!Framed(in)) return false;
  FalconReply r;
  for (int i = 0; i < 3; ++i)
    if (!GetWord(in + 1 + 4 * i, &r.encoder[i])) return false;
  if (in[13] < kNibbleBase || in[13] > kNibbleBase + 0x7F) return false;
  const uint8_t b = in[13] - kNibbleBase;
  r.buttons = b & 0x0F;
  r.homed_axes = (b >> 4) & 7;
  *reply = r;
  return true;
}

size_t StripFtdiStatus(const uint8_t* raw, size_t n, uint8_t* out, size_t usb_packet_size) {
  size_t m = 0;
  for (size_t start = 0; start < n; start += usb_packet_size) {
    const size_t end = start + usb_packet_size < n ? start + usb_packet_size : n;
    for (size_t i = start + 2; i < end; ++i) out[m++] = raw[i];
  }
  return m;
}

void FalconPacketParser::Push(const uint8_t* data, size_t n) {
  if (n >= kCapacity) {  // keep only the newest bytes
    data += n - kCapacity;
    garbage_ += size_ + (n - kCapacity);
    n = kCapacity;
    size_ = 0;
  }
  if (size_ + n > kCapacity) {
    const size_t drop = size_ + n - kCapacity;
    std::memmove(buf_, buf_ + drop, size_ - drop);
    size_ -= drop;
    garbage_ += drop;
  }
  std::memcpy(buf_ + size_, data, n);
  size_ += n;
}

bool FalconPacketParser::Next(FalconReply* reply) {
  size_t i = 0;
  bool found = false;
  while (i + kFalconPacketSize <= size_) {
    if (buf_[i] == '<' && DecodeReply(buf_ + i, reply)) {
      i += kFalconPacketSize;
      found = true;
      break;
    }
    ++i;
    ++garbage_;
  }
  // Keep a possible partial frame at the tail.
  if (!found) {
    while (i < size_ && buf_[i] != '<') {
      ++i;
      ++garbage_;
    }
  }
  std::memmove(buf_, buf_ + i, size_ - i);
  size_ -= i;
  return found;
}

}  // namespace hapcine
