#include "haptics/falcon_protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace hapcine {
namespace {

std::vector<uint8_t> Bytes(const uint8_t* p, size_t n) { return std::vector<uint8_t>(p, p + n); }

TEST(FalconProtocol, EncodesCommandAsComputedByHand) {
  // Torques 1, -1, 0x1234; homing + green LED. By hand from the notes:
  //   1      = 0x0001 -> nibbles (LSN first) 1 0 0 0 -> 42 41 41 41
  //   -1     = 0xFFFF -> F F F F                     -> 50 50 50 50
  //   0x1234 ->          4 3 2 1                     -> 45 44 43 42
  //   flags = 1 (homing) | 2 (green) = 3            -> 44; byte 14 = 41.
  FalconCommand c;
  c.torque[0] = 1;
  c.torque[1] = -1;
  c.torque[2] = 0x1234;
  c.homing = true;
  c.leds = 0x02;
  uint8_t out[16];
  EncodeCommand(c, out);
  const std::vector<uint8_t> expected = {0x3C, 0x42, 0x41, 0x41, 0x41, 0x50, 0x50, 0x50,
                                         0x50, 0x45, 0x44, 0x43, 0x42, 0x44, 0x41, 0x3E};
  EXPECT_EQ(Bytes(out, 16), expected);
  FalconCommand back;
  ASSERT_TRUE(DecodeCommand(out, &back));
  EXPECT_EQ(back.torque[2], 0x1234);
  EXPECT_TRUE(back.homing);
  EXPECT_EQ(back.leds, 0x02);
}

TEST(FalconProtocol, DecodesReplyComputedByHand) {
  // Encoders -300 (0xFED4: nibbles 4 D E F), 0, 32767 (0x7FFF: F F F 7);
  // byte 13 = 0x41 + (buttons 4 = centre | homed 7 << 4 = 0x70) = 0xB5.
  const uint8_t in[16] = {'<',  0x45, 0x4E, 0x4F, 0x50, 0x41, 0x41, 0x41,
                          0x41, 0x50, 0x50, 0x50, 0x48, 0xB5, 0x41, '>'};
  FalconReply r;
  ASSERT_TRUE(DecodeReply(in, &r));
  EXPECT_EQ(r.encoder[0], -300);
  EXPECT_EQ(r.encoder[1], 0);
  EXPECT_EQ(r.encoder[2], 32767);
  EXPECT_EQ(r.buttons, 4);
  EXPECT_EQ(r.homed_axes, 7);
  uint8_t again[16];
  EncodeReply(r, again);
  EXPECT_EQ(Bytes(again, 16), Bytes(in, 16));
}

TEST(FalconProtocol, RejectsMalformedFrames) {
  uint8_t good[16];
  EncodeReply(FalconReply(), good);
  FalconReply r;
  ASSERT_TRUE(DecodeReply(good, &r));
  for (int i : {0, 15}) {
    uint8_t bad[16];
    std::copy(good, good + 16, bad);
    bad[i] = 'x';
    EXPECT_FALSE(DecodeReply(bad, &r)) << i;
  }
  uint8_t bad[16];
  std::copy(good, good + 16, bad);
  bad[5] = 0x40;  // below 'A': not a nibble
  EXPECT_FALSE(DecodeReply(bad, &r));
  bad[5] = 0x51;  // above 'P'
  EXPECT_FALSE(DecodeReply(bad, &r));
  FalconCommand c;
  EXPECT_FALSE(DecodeCommand(bad, &c));
}

TEST(FalconProtocol, TorquesSaturateInsteadOfWrapping) {
  EXPECT_EQ(SaturateTorque(40000), 32767);
  EXPECT_EQ(SaturateTorque(-40000), -32767);
  EXPECT_EQ(SaturateTorque(1e300), 32767);
  EXPECT_EQ(SaturateTorque(-std::numeric_limits<double>::infinity()), -32767);
  EXPECT_EQ(SaturateTorque(std::nan("")), 0);
  EXPECT_EQ(SaturateTorque(4.9e-324), 0);  // denormal
  EXPECT_EQ(SaturateTorque(-12.6), -13);
}

TEST(FalconProtocol, StripsTwoStatusBytesPer64BytePacket) {
  std::vector<uint8_t> raw(100);
  for (size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<uint8_t>(i);
  std::vector<uint8_t> out(100);
  const size_t n = StripFtdiStatus(raw.data(), raw.size(), out.data());
  ASSERT_EQ(n, 96u);  // 62 + 34
  EXPECT_EQ(out[0], 2);
  EXPECT_EQ(out[61], 63);
  EXPECT_EQ(out[62], 66);  // bytes 64, 65 were the second packet's status
  EXPECT_EQ(StripFtdiStatus(raw.data(), 2, out.data()), 0u);  // status-only packet
}

TEST(FalconProtocol, ParserReframesSplitStreamsAndSkipsGarbage) {
  FalconReply a, b;
  a.encoder[0] = 123;
  b.encoder[2] = -77;
  b.homed_axes = 5;
  uint8_t pa[16], pb[16];
  EncodeReply(a, pa);
  EncodeReply(b, pb);
  std::vector<uint8_t> stream = {'x', '>', 0x41};
  stream.insert(stream.end(), pa, pa + 16);
  stream.insert(stream.end(), {'<', 'A'});  // a truncated frame
  stream.insert(stream.end(), pb, pb + 16);
  FalconPacketParser parser;
  FalconReply r;
  parser.Push(stream.data(), 10);  // split mid-frame
  EXPECT_FALSE(parser.Next(&r));
  parser.Push(stream.data() + 10, stream.size() - 10);
  ASSERT_TRUE(parser.Next(&r));
  EXPECT_EQ(r.encoder[0], 123);
  ASSERT_TRUE(parser.Next(&r));
  EXPECT_EQ(r.encoder[2], -77);
  EXPECT_EQ(r.homed_axes, 5);
  EXPECT_FALSE(parser.Next(&r));
  EXPECT_GT(parser.garbage_bytes(), 0u);
  // Overflow keeps the newest bytes and still finds frames.
  std::vector<uint8_t> junk(1000, 'z');
  parser.Push(junk.data(), junk.size());
  parser.Push(pa, 16);
  ASSERT_TRUE(parser.Next(&r));
  EXPECT_EQ(r.encoder[0], 123);
}

}  // namespace
}  // namespace hapcine
