#include "haptics/falcon_firmware.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "haptics/fake_falcon_transport.h"

namespace hapcine {
namespace {

std::vector<uint8_t> Image(size_t n = 8492) {
  std::vector<uint8_t> img(n);
  for (size_t i = 0; i < n; ++i) img[i] = static_cast<uint8_t>((i * 37 + 11) & 0xFF);
  return img;
}

FirmwareOptions Fast() {
  FirmwareOptions o;
  o.handshake_timeout_ms = 2;
  o.echo_timeout_ms = 20;
  return o;
}

TEST(FalconFirmware, LoadsOnTheFirstAttemptAndEntersNormalMode) {
  FakeFalconTransport fake(Image());
  EXPECT_FALSE(FalconFirmwareRunning(fake, 5));
  EXPECT_EQ(LoadFalconFirmware(fake, Image(), Fast()), 1);
  EXPECT_EQ(fake.mode(), FakeFalconTransport::Mode::kRunning);
  EXPECT_EQ(fake.baud_divisor(), ftdi::kBaudNormal);
  EXPECT_EQ(fake.latency_ms(), 1);
  EXPECT_TRUE(FalconFirmwareRunning(fake, 5));
}

TEST(FalconFirmware, RepeatsTheHandshakeUntilTheBootloaderAnswers) {
  FakeFalconTransport fake(Image(300));
  fake.ignore_handshakes = 7;
  EXPECT_EQ(LoadFalconFirmware(fake, Image(300), Fast()), 1);
  EXPECT_EQ(fake.handshakes_seen(), 8);
}

TEST(FalconFirmware, EchoMismatchIsRetriedThenSucceeds) {
  FakeFalconTransport fake(Image());
  fake.corrupt_echo_attempts = 2;
  std::vector<std::string> lines;
  EXPECT_EQ(
      LoadFalconFirmware(fake, Image(), Fast(), [&](const std::string& l) { lines.push_back(l); }),
      3);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("echo mismatch at byte 100"), std::string::npos) << lines[0];
}

TEST(FalconFirmware, PersistentMismatchGivesAClearErrorAfterTheRetries) {
  FakeFalconTransport fake(Image());
  fake.corrupt_echo_attempts = 1000;
  FirmwareOptions o = Fast();
  o.max_attempts = 4;
  try {
    LoadFalconFirmware(fake, Image(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("after 4 attempts"), std::string::npos) << m;
    EXPECT_NE(m.find("echo mismatch"), std::string::npos) << m;
  }
  EXPECT_EQ(fake.load_attempts(), 4);
}

TEST(FalconFirmware, ACancelledLoadStopsAtTheNextCheck) {
  FakeFalconTransport fake(Image());
  fake.corrupt_echo_attempts = 1000;
  FirmwareOptions o = Fast();
  o.max_attempts = 100;
  int polls = 0;
  o.cancelled = [&polls] { return ++polls > 3; };
  try {
    LoadFalconFirmware(fake, Image(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cancelled"), std::string::npos) << e.what();
  }
  EXPECT_LE(fake.load_attempts(), 3);
}

TEST(FalconFirmware, WrongImageStreamsButDoesNotBoot) {
  FakeFalconTransport fake(Image());
  FirmwareOptions o = Fast();
  o.max_attempts = 2;
  std::vector<uint8_t> wrong = Image();
  wrong[5000] ^= 1;
  try {
    LoadFalconFirmware(fake, wrong, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not answer"), std::string::npos) << e.what();
  }
}

TEST(FalconFirmware, SilentDeviceAndUnpluggedDeviceFail) {
  FakeFalconTransport fake(Image(100));
  fake.ignore_handshakes = 1000000;
  FirmwareOptions o = Fast();
  o.max_attempts = 2;
  o.handshake_tries = 3;
  EXPECT_THROW(LoadFalconFirmware(fake, Image(100), o), Error);
  FakeFalconTransport gone(Image(100));
  gone.unplugged = true;
  try {
    LoadFalconFirmware(gone, Image(100), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("control transfer failed"), std::string::npos) << e.what();
  }
}

TEST(FalconFirmware, FirmwareFileErrorsAreClear) {
  EXPECT_THROW(ReadFirmwareFile(""), Error);
  EXPECT_THROW(ReadFirmwareFile("/nonexistent/nVent_firmware.bin"), Error);
  const std::string empty = std::string(HAPCINE_BINARY_DIR) + "/empty_firmware_test.bin";
  { std::ofstream(empty, std::ios::binary); }
  EXPECT_THROW(ReadFirmwareFile(empty), Error);
  const std::string ok = std::string(HAPCINE_BINARY_DIR) + "/fake_firmware_test.bin";
  {
    std::ofstream f(ok, std::ios::binary);
    const auto img = Image(1000);
    f.write(reinterpret_cast<const char*>(img.data()), img.size());
  }
  EXPECT_EQ(ReadFirmwareFile(ok), Image(1000));
  std::remove(empty.c_str());
  std::remove(ok.c_str());
}

// Not a regular file: refused with one line, never read (/dev/zero never
// ends; a directory used to read as an empty file).
TEST(FalconFirmware, RefusesWhatIsNotARegularFile) {
  const std::string dir = HAPCINE_BINARY_DIR;
  for (const std::string& bad : {std::string("/dev/zero"), dir}) {
    try {
      ReadFirmwareFile(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), bad + (bad == dir ? ": is a directory" : ": not a regular file"));
    }
  }
}

}  // namespace
}  // namespace hapcine
