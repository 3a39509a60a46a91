#include "haptics/sim_device.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "haptics/safety.h"

namespace hapcine {
namespace {

// Equation 7 with the defaults of the player (k = 300 N/m, d = 2 N s/m),
// through the safety layer, at 1 kHz.
struct StepResult {
  double final_m = 0;
  double settle_s = 0;   // last time outside +-5% of the step around the final value
  double overshoot = 0;  // peak / final - 1
};

StepResult RunStep(SimDeviceOptions so, double step_m, double k = 300, double d = 2, double seconds = 3) {
  SimDevice dev(so);
  dev.Open();
  ActuatorSafety safety(SafetyOptions(), dev.MaxForceN());
  DeviceState s = dev.Exchange(Eigen::Vector3d::Zero());
  std::vector<double> x;
  const int n = static_cast<int>(seconds * 1000);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d target = safety.FilterTarget(Eigen::Vector3d(step_m, 0, 0));
    const Eigen::Vector3d f = safety.FilterForce(k * (target - s.pos_m) - d * s.vel_m_s, 1.0);
    s = dev.Exchange(f);
    x.push_back(dev.true_pos_m().x());
  }
  StepResult r;
  r.final_m = x.back();
  double peak = 0;
  for (int i = 0; i < n; ++i) {
    peak = std::max(peak, x[i]);
    if (std::abs(x[i] - r.final_m) > 0.05 * step_m) r.settle_s = (i + 1) / 1000.0;
  }
  r.overshoot = peak / r.final_m - 1;
  return r;
}

TEST(SimDevice, FollowsA1cmStepWithinTheDocumentedSettlingTime) {
  const StepResult r = RunStep(SimDeviceOptions(), 0.01);
  // Documented in docs/player.md: with the default hand (10 N/m) the grip
  // settles at k/(k + k_hand) = 97% of the step, within 5% of the step in
  // under 0.6 s (measured 0.44 s), overshoot below 60% (measured 47%: d = 2
  // is light damping for 0.5 kg).
  EXPECT_NEAR(r.final_m, 0.01 * 300 / 310, 0.0005);
  EXPECT_LT(r.settle_s, 0.6);
  EXPECT_LT(r.overshoot, 0.6);
  std::printf("1 cm step: final %.2f mm, settling (5%%) %.3f s, overshoot %.0f%%\n", r.final_m * 1e3, r.settle_s,
              r.overshoot * 100);
}

TEST(SimDevice, QuantisationMatchesTheIdealModelClosely) {
  SimDeviceOptions ideal;
  ideal.falcon_quantisation = false;
  const StepResult a = RunStep(SimDeviceOptions(), 0.01), b = RunStep(ideal, 0.01);
  EXPECT_NEAR(a.final_m, b.final_m, 3e-4);  // encoder resolution ~0.1 mm
}

TEST(SimDevice, EndStopsHoldAgainstTheMaximumForce) {
  SimDevice dev;
  dev.Open();
  for (int i = 0; i < 3000; ++i) dev.Exchange(Eigen::Vector3d(0, 9, 0));
  EXPECT_LT(dev.true_pos_m().y(), 0.0606);
  EXPECT_GT(dev.true_pos_m().y(), 0.059);
}

TEST(SimDevice, NonFiniteForceRendersNothing) {
  SimDevice dev;
  dev.Open();
  for (int i = 0; i < 100; ++i) dev.Exchange(Eigen::Vector3d(std::nan(""), 1e300, 0));
  EXPECT_TRUE(dev.true_pos_m().allFinite());
  EXPECT_LT(dev.true_pos_m().norm(), 1e-9);
}

TEST(SimDevice, ReportsUnhomedThenHomedAndNotOpen) {
  SimDeviceOptions o;
  o.homed_after_exchanges = 3;
  SimDevice dev(o);
  EXPECT_EQ(dev.Exchange(Eigen::Vector3d::Zero()).fault, DeviceFault::kNotOpen);
  dev.Open();
  EXPECT_FALSE(dev.Exchange(Eigen::Vector3d(0, 0, 5)).homed);
  dev.Exchange(Eigen::Vector3d::Zero());
  dev.Exchange(Eigen::Vector3d::Zero());
  EXPECT_TRUE(dev.Exchange(Eigen::Vector3d::Zero()).homed);
  EXPECT_LT(dev.true_pos_m().norm(), 1e-12);  // no force while unhomed
}

TEST(SimDevice, OptionsAreChecked) {
  SimDeviceOptions o;
  o.device_mass_kg = 0;
  EXPECT_THROW(SimDevice{o}, UsageError);
  o = SimDeviceOptions();
  o.substeps = 0;
  EXPECT_THROW(SimDevice{o}, UsageError);
}

}  // namespace
}  // namespace hapcine
