#include "player/play.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "haptics/fake_falcon_transport.h"
#include "haptics/safety.h"
#include "player/mpv_clock.h"

namespace hapcine {
namespace {
namespace fs = std::filesystem;

// One folder per test: ctest runs the tests of this file in parallel
// processes, and a shared folder let one test read the fake firmware file
// while another was rewriting it.
fs::path TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::path(HAPCINE_BINARY_DIR) / "play_test_tmp" /
                     (info ? std::string(info->test_suite_name()) + "." + info->name() : "none");
  fs::create_directories(d);
  return d;
}

void WriteTrack(const fs::path& path, double duration_s) {
  HapticTrack t;
  t.rate_hz = 50;
  t.model = "cinematic";
  t.source = "test";
  for (int i = 0; i <= static_cast<int>(duration_s * 50); ++i) {
    HapticSample s;
    s.time_s = i / 50.0;
    s.pos_m[1] = Eigen::Vector3d(0.01, 0, 0);
    t.samples.push_back(s);
  }
  WriteHapticTrackFile(t, path.string());
}

// Options for a short play of `track` on the wall clock (no mpv), quick ramps.
PlayOptions WallClockPlay(const fs::path& track) {
  PlayOptions o;
  o.track = track.string();
  o.wall_clock = true;
  o.realtime = false;
  o.loop.start_ramp_s = 0.05;
  o.loop.end_ramp_s = 0.05;
  o.max_run_s = 10;
  return o;
}

TEST(Play, FindsTheSiblingTrackOrSaysWhereItLooked) {
  const fs::path d = TempDir();
  WriteTrack(d / "clip.haptic.csv", 0.2);
  EXPECT_EQ(ResolveTrackPath((d / "clip.mp4").string(), ""), (d / "clip.haptic.csv").string());
  try {
    ResolveTrackPath((d / "other.mp4").string(), "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other.haptic.csv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ResolveTrackPath("x.mp4", (d / "missing.haptic.csv").string()), Error);
}

TEST(Play, WallClockPlayOnTheSimFinishes) {
  const fs::path d = TempDir();
  WriteTrack(d / "short.haptic.csv", 0.2);
  PlayOptions o = WallClockPlay(d / "short.haptic.csv");
  o.device = "sim";
  o.print_stats = true;
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished);
  EXPECT_GT(r.stats.ticks, 100);
  EXPECT_NE(log.str().find("period p50"), std::string::npos) << log.str();
}

TEST(Play, BadOptionsAndNoDeviceAreClear) {
  PlayOptions o;
  o.device = "joystick";
  o.video = "x.mp4";
  std::ostringstream log;
  EXPECT_THROW(Play(o, log), UsageError);
  o.device = "falcon";
  o.video.clear();
  o.wall_clock = true;
  const fs::path d = TempDir();
  WriteTrack(d / "f.haptic.csv", 0.2);
  o.track = (d / "f.haptic.csv").string();
  try {
    Play(o, log);
    FAIL() << "no Falcon here, yet it played";
  } catch (const Error& e) {
    // This machine has no Falcon: the message says what was found.
    EXPECT_NE(std::string(e.what()).find("0403:cb48"), std::string::npos) << e.what();
  }
}

// A test-pattern clip of `seconds` with a tone (ffmpeg CLI); "" without ffmpeg.
std::string MakeClip(const std::string& name, int seconds) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) return "";
  const fs::path video = TempDir() / name;
  if (!fs::exists(video)) {
    const std::string d = std::to_string(seconds);
    const std::string cmd = "ffmpeg -loglevel error -y -f lavfi -i testsrc=duration=" + d +
                            ":size=64x48:rate=25 -f lavfi -i sine=duration=" + d +
                            " -pix_fmt yuv420p -shortest " + video.string();
    if (std::system(cmd.c_str()) != 0) return "";
  }
  return video.string();
}

TEST(Play, HeadlessMpvPlaysAGeneratedClip) {
  const fs::path d = TempDir();
  const std::string clip = MakeClip("tiny.mp4", 1);
  if (clip.empty()) GTEST_SKIP() << "ffmpeg CLI not installed";
  const fs::path video = clip;
  WriteTrack(d / "tiny.haptic.csv", 1.0);
  PlayOptions o;
  o.video = video.string();
  o.headless = true;
  o.device = "sim";
  o.loop.end_ramp_s = 0.1;
  o.max_run_s = 10;
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished) << log.str();
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // mpv's clock ran through the 1 s clip (25 fps: about one update per
  // frame), and the loop's extrapolated media time stayed within a few
  // frames of what mpv reported.
  EXPECT_GT(r.stats.ticks, 900);
  EXPECT_GT(r.stats.extrapolation_error.count(), 10);
  EXPECT_LT(r.stats.extrapolation_error.Quantile(0.5), 0.040);
  // A track 3 s longer than the clip is reported.
  WriteTrack(d / "long.haptic.csv", 4.0);
  o.track = (d / "long.haptic.csv").string();
  o.strict_duration = true;
  EXPECT_THROW(Play(o, log), Error);
}

TEST(Play, MpvPauseAndSeekReachTheClock) {
  const std::string video = MakeClip("three.mp4", 3);
  if (video.empty()) GTEST_SKIP() << "ffmpeg CLI not installed";
  MpvOptions mo;
  mo.headless = true;
  MpvClock mpv(video, mo);
  mpv.WaitLoaded(20);
  auto wait_for = [&](const std::function<bool(const ClockReading&)>& ok) {
    for (int i = 0; i < 400; ++i) {
      if (ok(mpv.Read())) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  };
  ASSERT_TRUE(wait_for([](const ClockReading& r) { return r.valid && !r.paused; }));
  EXPECT_NEAR(mpv.duration_s(), 3.0, 0.1);
  mpv.SetPause(true);
  ASSERT_TRUE(wait_for([](const ClockReading& r) { return r.paused; }));
  const double held = mpv.Read().media_s;
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(mpv.Read().media_s, held) << "media time moved while paused";
  EXPECT_EQ(Extrapolate(mpv.Read(), SteadySeconds() + 1), held);
  const uint64_t seeks = mpv.Read().seek_serial;
  mpv.SeekAbsolute(2.0);
  ASSERT_TRUE(wait_for([&](const ClockReading& r) {
    return r.seek_serial > seeks && std::abs(r.media_s - 2.0) < 0.05;
  }));
  mpv.SetPause(false);
  ASSERT_TRUE(wait_for([](const ClockReading& r) { return r.eof; })) << "never reached the end";
}

// Hands Play() a transport whose fake Falcon stays with the test, so the
// test can read what the device was sent after Play() has closed it.
class SharedFakeTransport : public UsbTransport {
 public:
  explicit SharedFakeTransport(std::shared_ptr<FakeFalconTransport> fake) : fake_(std::move(fake)) {}
  bool Control(uint8_t request, uint16_t value) override { return fake_->Control(request, value); }
  int BulkWrite(const uint8_t* data, int n, int timeout_ms) override {
    return fake_->BulkWrite(data, n, timeout_ms);
  }
  int BulkRead(uint8_t* buf, int capacity, int timeout_ms) override {
    return fake_->BulkRead(buf, capacity, timeout_ms);
  }
  std::string Describe() const override { return fake_->Describe(); }

 private:
  std::shared_ptr<FakeFalconTransport> fake_;
};

// A seat of fake Falcons (the protocol byte for byte) behind Play().
struct FakeFalcons {
  std::vector<uint8_t> image = std::vector<uint8_t>(300, 0x3C);
  std::map<std::string, std::shared_ptr<FakeFalconTransport>> by_serial;
  std::string firmware_path;
  int corrupt_echo_attempts = 0;
  int ignore_handshakes = 0;

  explicit FakeFalcons(std::vector<std::string> serials) {
    firmware_path = (TempDir() / "fake_fw.bin").string();
    std::ofstream(firmware_path, std::ios::binary)
        .write(reinterpret_cast<const char*>(image.data()), image.size());
    for (const auto& s : serials) by_serial[s] = nullptr;
  }
  void Install(PlayOptions* o) {
    o->device = "falcon";
    o->firmware = firmware_path;
    o->firmware_options.max_attempts = 3;
    o->firmware_options.handshake_timeout_ms = 2;
    o->firmware_options.echo_timeout_ms = 20;
    o->list_falcons = [this] {
      std::vector<UsbDeviceInfo> out;
      for (const auto& kv : by_serial) out.push_back({1, 2, kv.first, ""});
      return out;
    };
    o->open_falcon = [this](const std::string& serial) {
      auto fake = std::make_shared<FakeFalconTransport>(image);
      fake->corrupt_echo_attempts = corrupt_echo_attempts;
      fake->ignore_handshakes = ignore_handshakes;
      by_serial[serial] = fake;
      return std::unique_ptr<UsbTransport>(std::make_unique<SharedFakeTransport>(fake));
    };
  }
};

TEST(Play, FakeFalconsLoadFirmwareHomeAndEndWithZeroTorque) {
  const fs::path d = TempDir();
  WriteTrack(d / "falcon.haptic.csv", 0.3);
  FakeFalcons fakes({"FTB", "FTA", "FTC"});
  PlayOptions o = WallClockPlay(d / "falcon.haptic.csv");
  fakes.Install(&o);
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished) << log.str();
  // Three Falcons without a seat config: head, left, right in serial order.
  EXPECT_NE(log.str().find("falcon serial FTA -> head"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("falcon serial FTC -> right"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("all Falcons homed"), std::string::npos) << log.str();
  for (int a = 0; a < kNumActuators; ++a) EXPECT_EQ(r.last_sent_force_n[a], 0.0) << a;
  for (const auto& kv : fakes.by_serial) {
    ASSERT_NE(kv.second, nullptr);
    EXPECT_EQ(kv.second->mode(), FakeFalconTransport::Mode::kRunning);
    EXPECT_GT(kv.second->commands_seen(), 200);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(kv.second->last_command().torque[i], 0) << kv.first;
  }
}

TEST(Play, ASeatConfigMapsFalconsBySerialAndNamesAMissingOne) {
  const fs::path d = TempDir();
  WriteTrack(d / "falcon.haptic.csv", 0.3);
  FakeFalcons fakes({"FTA", "FTB"});
  const fs::path config = d / "seat.json";
  std::ofstream(config) << R"({"devices": [{"role": "right", "serial": "FTA"},
                                          {"role": "head", "serial": "FTB", "mount": "behind"}]})";
  PlayOptions o = WallClockPlay(d / "falcon.haptic.csv");
  fakes.Install(&o);
  o.seat_config = config.string();
  std::ostringstream log;
  const PlayResult r = Play(o, log);
  EXPECT_EQ(r.status, LoopStatus::kFinished) << log.str();
  EXPECT_EQ(r.last_sent_force_n[0], 0.0);   // head: FTB
  EXPECT_EQ(r.last_sent_force_n[1], -1.0);  // left: not configured
  EXPECT_EQ(r.last_sent_force_n[2], 0.0);   // right: FTA
  EXPECT_NE(log.str().find("opening falcon serial FTB"), std::string::npos) << log.str();
  // A configured serial that is not plugged in: named, with what was found.
  std::ofstream(config) << R"({"devices": [{"role": "left", "serial": "FTZ"}]})";
  try {
    Play(o, log);
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("FTZ"), std::string::npos) << m;
    EXPECT_NE(m.find("serial 'FTA'"), std::string::npos) << m;
  }
}

TEST(Play, FirmwareThatWillNotLoadIsRetriedThenAClearError) {
  const fs::path d = TempDir();
  WriteTrack(d / "falcon.haptic.csv", 0.3);
  FakeFalcons fakes({"FTA"});
  fakes.corrupt_echo_attempts = 1000;
  PlayOptions o;
  fakes.Install(&o);
  o.track = (d / "falcon.haptic.csv").string();
  o.wall_clock = true;
  std::ostringstream log;
  try {
    Play(o, log);
    FAIL() << "played with firmware that never loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("firmware load failed after 3 attempts"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NE(log.str().find("firmware attempt 2/3 failed"), std::string::npos) << log.str();
  // Ctrl-C while the firmware keeps failing: stopped at once, not after
  // every retry.
  // A bootloader that never answers: each attempt takes 100 handshakes.
  fakes.ignore_handshakes = 1 << 30;
  o.firmware_options.max_attempts = 1000;
  std::thread ctrl_c([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    kill(getpid(), SIGINT);
  });
  const double t0 = SteadySeconds();
  PlayResult stopped;
  try {
    stopped = Play(o, log);
  } catch (...) {
    ctrl_c.join();
    throw;
  }
  ctrl_c.join();
  EXPECT_EQ(stopped.status, LoopStatus::kStopped);
  EXPECT_EQ(stopped.stop_signal, SIGINT);
  EXPECT_LT(SteadySeconds() - t0, 3.0);
  EXPECT_EQ(stopped.stats.ticks, 0);
  o.firmware_options.max_attempts = 3;
  fakes.ignore_handshakes = 0;
  // A firmware path that does not exist is named before any USB work.
  o.firmware = (d / "no_such_firmware.bin").string();
  try {
    Play(o, log);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_firmware.bin"), std::string::npos) << e.what();
  }
  // No Falcon at all: the message says so.
  o.firmware.clear();
  o.list_falcons = [] { return std::vector<UsbDeviceInfo>(); };
  try {
    Play(o, log);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no USB device 0403:cb48"), std::string::npos) << e.what();
  }
}

TEST(Play, SigtermMidPlayStopsWithZeroForceOnEveryDevice) {
  const fs::path d = TempDir();
  WriteTrack(d / "long.haptic.csv", 5.0);
  for (int sig : {SIGTERM, SIGINT}) {
    const PlayOptions o = WallClockPlay(d / "long.haptic.csv");
    std::thread killer([sig] {
      std::this_thread::sleep_for(std::chrono::milliseconds(600));
      kill(getpid(), sig);
    });
    std::ostringstream log;
    const PlayResult r = Play(o, log);
    killer.join();
    EXPECT_EQ(r.status, LoopStatus::kStopped) << log.str();
    EXPECT_EQ(r.stop_signal, sig);
    EXPECT_GT(r.stats.ticks, 300);
    for (int a = 0; a < kNumActuators; ++a) EXPECT_EQ(r.last_sent_force_n[a], 0.0) << a;
  }
}

}  // namespace
}  // namespace hapcine
