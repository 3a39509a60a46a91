#include "core/haptic_track.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {

HapticTrack MakeTrack(int n) {
  HapticTrack t;
  t.rate_hz = 100;
  t.model = "cinematic";
  t.source = "clip with spaces.camera.csv";
  for (int i = 0; i < n; ++i) {
    HapticSample s;
    s.time_s = i / 100.0;
    s.pos_m[0] = {0.001 * i, 0, -0.0005 * i};
    s.pos_m[1] = {0, -0.002 * i, 0};
    s.pos_m[2] = {0, 0.002 * i, 0};
    s.shot = 0;
    s.effect = i > 2 ? "dutch_angle" : "";
    t.samples.push_back(s);
  }
  return t;
}

TEST(HapticTrackTest, RoundTrip) {
  const HapticTrack t = MakeTrack(10);
  std::stringstream ss;
  WriteHapticTrack(t, ss);
  const HapticTrack r = ReadHapticTrack(ss, "mem");
  EXPECT_EQ(r.rate_hz, 100);
  EXPECT_EQ(r.model, "cinematic");
  EXPECT_EQ(r.source, "clip with spaces.camera.csv");
  ASSERT_EQ(r.samples.size(), 10u);
  for (size_t i = 0; i < 10; ++i) {
    EXPECT_NEAR(r.samples[i].time_s, t.samples[i].time_s, 1e-9);
    for (int a = 0; a < kNumActuators; ++a) {
      EXPECT_LT((r.samples[i].pos_m[a] - t.samples[i].pos_m[a]).norm(), 1e-7);
    }
    EXPECT_EQ(*r.samples[i].shot, 0);
  }
  EXPECT_EQ(*r.samples[5].effect, "dutch_angle");
}

TEST(HapticTrackTest, SourceAndMetadataWithLineBreaksRoundTrip) {
  HapticTrack t = MakeTrack(4);
  t.source = std::string("film\nname\r,a=b\\c\x01\x1f\x7f é 日本 .camera.csv");
  t.metadata["effects_from"] = "keys\n# model=none\n.csv";
  std::stringstream ss;
  WriteHapticTrack(t, ss);
  const HapticTrack r = ReadHapticTrack(ss, "mem");
  EXPECT_EQ(r.source, t.source);
  EXPECT_EQ(r.model, "cinematic");
  EXPECT_EQ(r.metadata.at("effects_from"), "keys\n# model=none\n.csv");
  EXPECT_EQ(r.samples.size(), 4u);
}

TEST(HapticTrackTest, SampleInterpolatesAndClamps) {
  const HapticTrack t = MakeTrack(10);
  Eigen::Vector3d out[kNumActuators];
  t.Sample(0.035, out);
  EXPECT_NEAR(out[0].x(), 0.0035, 1e-12);
  t.Sample(-5, out);
  EXPECT_EQ(out[1].y(), 0);
  t.Sample(99, out);
  EXPECT_NEAR(out[2].y(), 0.018, 1e-12);
  t.Sample(std::numeric_limits<double>::quiet_NaN(), out);  // NaN time -> first sample
  EXPECT_TRUE(out[0].allFinite());
  size_t hint = 0;
  for (double time = 0; time < 0.09; time += 0.001) {  // monotone walk with a hint
    t.Sample(time, out, &hint);
    EXPECT_NEAR(out[0].x(), 0.1 * time, 1e-9);
  }
  t.Sample(0.02, out, &hint);  // seek backwards with a stale hint
  EXPECT_NEAR(out[0].x(), 0.002, 1e-12);
}

TEST(HapticTrackTest, EmptyTrackSamplesZero) {
  HapticTrack t;
  Eigen::Vector3d out[kNumActuators];
  out[0] = {1, 1, 1};
  t.Sample(1.0, out);
  EXPECT_EQ(out[0], Eigen::Vector3d::Zero());
}

void ExpectRejected(const std::string& text, const std::string& reason, int line) {
  std::stringstream ss(text);
  try {
    ReadHapticTrack(ss, "t.haptic.csv");
    FAIL() << "accepted:\n" << text;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("t.haptic.csv:" + std::to_string(line) + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(reason), std::string::npos) << msg;
  }
}

#define META "# rate_hz=1000\n# model=none\n# source=x.mp4\n"
#define HDR "time_s,head_x,head_y,head_z,left_x,left_y,left_z,right_x,right_y,right_z\n"
TEST(HapticTrackTest, RejectsMalformedInput) {
  ExpectRejected("", "no header", 0);
  ExpectRejected("# model=none\n# source=x\n" HDR "0,0,0,0,0,0,0,0,0,0\n", "rate_hz", 3);
  ExpectRejected("# rate_hz=-5\n# model=none\n# source=x\n" HDR, "not a positive rate", 4);
  ExpectRejected(META "time_s,head_x\n", "missing column 'head_y'", 4);
  ExpectRejected(META HDR "0,0,0,0,0,0,0,0,0,nan\n", "non-finite", 5);
  ExpectRejected(META HDR "0,0,0,0,0,0,0,0,0,0\n0.001,0,0\n", "truncated", 6);
  ExpectRejected(META HDR "0.1,0,0,0,0,0,0,0,0,0\n0.1,0,0,0,0,0,0,0,0,0\n", "not increasing", 6);
  ExpectRejected(META HDR "0,0,0,0,0,0,0,0,0,50\n", "beyond any workspace", 5);
  ExpectRejected(META HDR, "no data rows", 4);
}

TEST(HapticTrackTest, WriterRefusesNonFiniteAndLeavesNoFile) {
  HapticTrack t = MakeTrack(3);
  t.samples[1].pos_m[2].z() = std::numeric_limits<double>::infinity();
  const std::string file = ::testing::TempDir() + "/bad.haptic.csv";
  EXPECT_THROW(WriteHapticTrackFile(t, file), Error);
  EXPECT_FALSE(std::ifstream(file).good());
}

}  // namespace
}  // namespace hapcine
