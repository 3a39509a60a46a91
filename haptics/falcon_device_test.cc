#include "haptics/falcon_device.h"
#include "testpaths/test_paths.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "haptics/fake_falcon_transport.h"

namespace hapcine {
namespace {

std::vector<uint8_t> Image() { return std::vector<uint8_t>(500, 0x5A); }

std::string WriteImage() {
  const std::string path = std::string(HAPCINE_BINARY_DIR) + "/falcon_device_test_fw.bin";
  std::ofstream f(path, std::ios::binary);
  const auto img = Image();
  f.write(reinterpret_cast<const char*>(img.data()), img.size());
  return path;
}

struct Rig {
  FakeFalconTransport* fake;
  std::unique_ptr<FalconDevice> dev;
};

Rig MakeRig(bool preloaded = false, Eigen::Matrix3d mount = Eigen::Matrix3d::Identity()) {
  auto fake = std::make_unique<FakeFalconTransport>(Image());
  fake->firmware_preloaded = preloaded;
  Rig rig{fake.get(), nullptr};
  FalconDeviceOptions o;
  o.firmware_path = WriteImage();
  o.firmware.handshake_timeout_ms = 2;
  o.firmware.echo_timeout_ms = 20;
  o.max_silent_ticks = 5;
  o.seat_from_falcon = mount;
  rig.dev = std::make_unique<FalconDevice>(std::move(fake), o);
  return rig;
}

TEST(FalconDevice, OpenLoadsFirmwareThenHomesBeforeAnyForce) {
  Rig rig = MakeRig();
  rig.dev->Open();
  EXPECT_EQ(rig.dev->firmware_attempts(), 1);
  rig.fake->homing_packets_needed = 4;
  rig.fake->falcon_pos_m = FalconCentre() + Eigen::Vector3d(0.01, 0, 0);
  // Until homed: homing bit set, red LED, zero torque whatever is asked.
  for (int i = 0; i < 4; ++i) {
    const DeviceState s = rig.dev->Exchange(Eigen::Vector3d(0, 0, 5));
    EXPECT_TRUE(rig.fake->last_command().homing) << i;
    EXPECT_EQ(rig.fake->last_command().leds, static_cast<uint8_t>(Led::kRed));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(rig.fake->last_command().torque[k], 0);
    EXPECT_EQ(s.homed, i == 3);  // the 4th homing packet homes all axes
  }
  // Homed: homing bit off, green LED, a force gives torques.
  const DeviceState s = rig.dev->Exchange(Eigen::Vector3d(0, 0, 5));
  EXPECT_TRUE(s.homed);
  EXPECT_FALSE(rig.fake->last_command().homing);
  EXPECT_EQ(rig.fake->last_command().leds, static_cast<uint8_t>(Led::kGreen));
  int nonzero = 0;
  for (int k = 0; k < 3; ++k) nonzero += rig.fake->last_command().torque[k] != 0;
  EXPECT_EQ(nonzero, 3);
  // Position decoded through encoders + forward kinematics, seat frame,
  // relative to the centre: within the encoder resolution (~0.1 mm).
  EXPECT_NEAR(s.pos_m.x(), 0.01, 2e-4);
  EXPECT_NEAR(s.pos_m.y(), 0.0, 2e-4);
  EXPECT_NEAR(s.pos_m.z(), 0.0, 2e-4);
}

TEST(FalconDevice, MountRotationMapsFalconToSeatFrame) {
  const Eigen::Matrix3d behind = Eigen::Vector3d(-1, 1, -1).asDiagonal();
  Rig rig = MakeRig(true, behind);
  rig.dev->Open();
  EXPECT_EQ(rig.dev->firmware_attempts(), 0);  // already running
  rig.fake->homing_packets_needed = 1;
  rig.fake->falcon_pos_m = FalconCentre() + Eigen::Vector3d(0.01, 0.005, -0.02);
  DeviceState s;
  for (int i = 0; i < 3; ++i) s = rig.dev->Exchange(Eigen::Vector3d::Zero());
  EXPECT_NEAR(s.pos_m.x(), -0.01, 2e-4);
  EXPECT_NEAR(s.pos_m.y(), 0.005, 2e-4);
  EXPECT_NEAR(s.pos_m.z(), 0.02, 2e-4);
}

TEST(FalconDevice, TorquesSaturateAndNonFiniteForceSendsZero) {
  Rig rig = MakeRig(true);
  rig.dev->Open();
  rig.fake->homing_packets_needed = 1;
  for (int i = 0; i < 3; ++i) rig.dev->Exchange(Eigen::Vector3d::Zero());
  rig.dev->Exchange(Eigen::Vector3d(0, 0, 1e9));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(std::abs(rig.fake->last_command().torque[k]), 32767);
  rig.dev->Exchange(Eigen::Vector3d(std::nan(""), 0, 0));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(rig.fake->last_command().torque[k], 0);
  // A huge sideways force: the largest torque is at the limit and the three
  // keep the proportions of J^T F, so the rendered force keeps its direction.
  const Eigen::Vector3d f(1e9, 2e8, 0);
  rig.dev->Exchange(f);
  Eigen::Vector3d tau;
  ASSERT_TRUE(FalconKinematics().ForceToTorque(rig.fake->falcon_pos_m, f, &tau));
  const Eigen::Vector3d want = tau * (32767.0 / tau.cwiseAbs().maxCoeff());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(std::abs(rig.fake->last_command().torque[k]), std::abs(want[k]), 1.0) << k;
  }
}

TEST(FalconDevice, UnplugAndSilenceAreFaults) {
  Rig rig = MakeRig(true);
  rig.dev->Open();
  rig.fake->mute = true;
  DeviceState s;
  for (int i = 0; i < 5; ++i) s = rig.dev->Exchange(Eigen::Vector3d::Zero());
  EXPECT_EQ(s.fault, DeviceFault::kNoData);
  rig.fake->mute = false;
  EXPECT_EQ(rig.dev->Exchange(Eigen::Vector3d::Zero()).fault, DeviceFault::kNone);
  rig.fake->unplugged = true;
  EXPECT_EQ(rig.dev->Exchange(Eigen::Vector3d::Zero()).fault, DeviceFault::kTransferError);
}

TEST(FalconDevice, CloseSendsZeroTorqueAndExchangeAfterCloseIsAFault) {
  Rig rig = MakeRig(true);
  rig.dev->Open();
  rig.fake->homing_packets_needed = 1;
  for (int i = 0; i < 3; ++i) rig.dev->Exchange(Eigen::Vector3d(0, 3, 0));
  const int before = rig.fake->commands_seen();
  rig.dev->Close();
  EXPECT_GT(rig.fake->commands_seen(), before);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(rig.fake->last_command().torque[k], 0);
  EXPECT_EQ(rig.dev->Exchange(Eigen::Vector3d::Zero()).fault, DeviceFault::kNotOpen);
}

TEST(FalconDevice, MissingFirmwareFileIsAClearError) {
  auto fake = std::make_unique<FakeFalconTransport>(Image());
  FalconDeviceOptions o;  // no firmware_path
  FalconDevice dev(std::move(fake), o);
  try {
    dev.Open();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--firmware"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hapcine
