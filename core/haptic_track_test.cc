#include "core/haptic_track.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

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

// A track whose head x follows f at the given times (other coordinates 0).
HapticTrack CubicTrack(const std::vector<double>& times, double (*f)(double)) {
  HapticTrack t;
  t.rate_hz = 100;
  t.interpolation = TrackInterpolation::kMonotoneCubic;
  for (double time : times) {
    HapticSample s;
    s.time_s = time;
    s.pos_m[0].x() = f(time);
    t.samples.push_back(s);
  }
  return t;
}

double HeadXAt(const HapticTrack& t, double time) {
  Eigen::Vector3d out[kNumActuators];
  t.Sample(time, out);
  return out[0].x();
}

TEST(HapticTrackTest, MonotoneCubicIsExactOnConstantsLinesAndMonotoneQuadratics) {
  const std::vector<double> uneven = {1.0, 1.01, 1.03, 1.04, 1.07, 1.1, 1.12};
  const HapticTrack flat = CubicTrack(uneven, [](double) { return 0.03; });
  const HapticTrack line = CubicTrack(uneven, [](double x) { return 0.2 * x - 0.2; });
  const HapticTrack quad = CubicTrack(uneven, [](double x) { return 0.5 * x * x - 0.5; });
  for (double x = 1.0; x <= 1.12; x += 0.0007) {
    EXPECT_EQ(HeadXAt(flat, x), 0.03) << x;
    EXPECT_NEAR(HeadXAt(line, x), 0.2 * x - 0.2, 1e-15) << x;
    // The first and last intervals take the secant (a line): inner ones only.
    if (x > 1.01 && x < 1.1) {
      EXPECT_NEAR(HeadXAt(quad, x), 0.5 * x * x - 0.5, 1e-13) << x;
    }
  }
}

TEST(HapticTrackTest, MonotoneCubicFollowsASmoothMotionAt100HzWithoutVelocitySteps) {
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(i / 100.0);
  auto motion = [](double x) { return 0.04 * std::sin(2 * M_PI * 1.5 * x); };
  const HapticTrack t = CubicTrack(times, motion);
  HapticTrack linear = t;
  linear.interpolation = TrackInterpolation::kLinear;
  double max_cubic = 0, max_linear = 0;
  for (double x = 0.01; x < 1.99; x += 0.0005) {
    max_cubic = std::max(max_cubic, std::abs(HeadXAt(t, x) - motion(x)));
    max_linear = std::max(max_linear, std::abs(HeadXAt(linear, x) - motion(x)));
  }
  EXPECT_LT(max_cubic, 0.03e-3);  // well under the 0.1 mm budget
  EXPECT_LT(max_cubic, 0.6 * max_linear);  // about half the error of straight lines
  // Unlike straight lines, no step in velocity at every row (a 100 Hz buzz
  // in the force): the slopes either side of a row agree.
  double cubic_jump = 0, linear_jump = 0;
  const double e = 1e-6;
  for (int i = 10; i < 190; ++i) {
    const double x = i / 100.0;
    auto jump = [&](const HapticTrack& tr) {
      return std::abs((HeadXAt(tr, x + e) - HeadXAt(tr, x)) - (HeadXAt(tr, x) - HeadXAt(tr, x - e))) / e;
    };
    cubic_jump = std::max(cubic_jump, jump(t));
    linear_jump = std::max(linear_jump, jump(linear));
  }
  EXPECT_LT(cubic_jump, 1e-3);    // m/s
  EXPECT_GT(linear_jump, 10e-3);
}

TEST(HapticTrackTest, MonotoneCubicNeverOvershootsAStepASpikeOrAClamp) {
  std::vector<double> times;
  for (int i = 0; i < 12; ++i) times.push_back(i / 100.0);
  const HapticTrack step = CubicTrack(times, [](double x) { return x < 0.055 ? 0.0 : 0.045; });
  const HapticTrack spike =
      CubicTrack(times, [](double x) { return std::abs(x - 0.05) < 1e-9 ? -0.045 : 0.0; });
  // A motion clamped at the workspace edge: a plateau the curve must not leave.
  const HapticTrack clamped =
      CubicTrack(times, [](double x) { return std::min(0.045, 0.8 * x); });
  double previous = 0;
  for (double x = 0; x <= 0.11; x += 0.0003) {
    const double v = HeadXAt(step, x);
    EXPECT_GE(v, 0) << x;
    EXPECT_LE(v, 0.045) << x;
    EXPECT_GE(v, previous) << x;  // monotone across the step
    previous = v;
    EXPECT_LE(HeadXAt(spike, x), 0) << x;
    EXPECT_GE(HeadXAt(spike, x), -0.045) << x;
    EXPECT_LE(HeadXAt(clamped, x), 0.045) << x;
  }
}

TEST(HapticTrackTest, MonotoneCubicOnOneOrTwoSamples) {
  const HapticTrack one = CubicTrack({2.0}, [](double) { return 0.01; });
  EXPECT_EQ(HeadXAt(one, 1.0), 0.01);
  EXPECT_EQ(HeadXAt(one, 2.0), 0.01);
  EXPECT_EQ(HeadXAt(one, 3.0), 0.01);
  const HapticTrack two = CubicTrack({0.0, 0.01}, [](double x) { return x; });
  for (double x = 0; x <= 0.01; x += 0.001) EXPECT_NEAR(HeadXAt(two, x), x, 1e-15) << x;
  EXPECT_EQ(HeadXAt(two, 5.0), 0.01);
}

TEST(HapticTrackTest, ATrackWithoutInterpolationLineIsLinearAsBefore) {
  std::stringstream file(META HDR "0,0,0,0,0,0,0,0,0,0\n0.001,0.003,0,0,0,0,0,0,0,0\n"
                                  "0.002,0.0031,0,0,0,0,0,0,0,0\n0.003,-0.002,0,0,0,0,0,0,0,0\n");
  const HapticTrack t = ReadHapticTrack(file, "old.haptic.csv");
  EXPECT_EQ(t.interpolation, TrackInterpolation::kLinear);
  for (double x : {0.0004, 0.0013, 0.0027}) {
    const size_t i = static_cast<size_t>(x * 1000);
    const double w = (x - t.samples[i].time_s) / (t.samples[i + 1].time_s - t.samples[i].time_s);
    const double expected = (1 - w) * t.samples[i].pos_m[0].x() + w * t.samples[i + 1].pos_m[0].x();
    EXPECT_EQ(HeadXAt(t, x), expected) << x;  // bit for bit
  }
  std::stringstream written;
  WriteHapticTrack(t, written);
  EXPECT_EQ(written.str().find("interpolation"), std::string::npos);
}

TEST(HapticTrackTest, InterpolationRoundTripsAndFollowsTheRate) {
  EXPECT_EQ(InterpolationForRate(1000), TrackInterpolation::kLinear);
  EXPECT_EQ(InterpolationForRate(2000), TrackInterpolation::kLinear);
  EXPECT_EQ(InterpolationForRate(100), TrackInterpolation::kMonotoneCubic);
  HapticTrack t = MakeTrack(5);
  t.interpolation = TrackInterpolation::kMonotoneCubic;
  std::stringstream ss;
  WriteHapticTrack(t, ss);
  EXPECT_NE(ss.str().find("# interpolation=monotone_cubic\n"), std::string::npos);
  const HapticTrack r = ReadHapticTrack(ss, "mem");
  EXPECT_EQ(r.interpolation, TrackInterpolation::kMonotoneCubic);
  EXPECT_EQ(r.metadata.count("interpolation"), 0u);
  ExpectRejected("# rate_hz=100\n# model=none\n# source=x\n# interpolation=sinc\n" HDR
                 "0,0,0,0,0,0,0,0,0,0\n",
                 "interpolation 'sinc'", 5);
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
