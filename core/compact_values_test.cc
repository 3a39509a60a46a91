#include "core/compact_values.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>

#include "core/rotation.h"

namespace hapcine {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(StoredFloatTest, HoldsTheNearestFloatAndComputesInDouble) {
  StoredFloat v(55.3);
  EXPECT_EQ(double(v), double(55.3f));
  v *= 2;
  EXPECT_EQ(double(v), double(float(2 * double(55.3f))));
  const StoredFloat half(1.5);
  EXPECT_EQ(half / 4, 0.375);
  EXPECT_EQ(StoredFloat(1.0 / 3) / 3, double(float(1.0 / 3)) / 3);  // not float division
}

TEST(OptionalFloatTest, ReadsLikeStdOptional) {
  OptionalFloat f;
  EXPECT_FALSE(f.has_value());
  EXPECT_FALSE(f);
  EXPECT_EQ(f.value_or(7), 7);
  EXPECT_THROW(f.value(), std::bad_optional_access);
  EXPECT_EQ(f, std::nullopt);
  f = 1843.92;
  ASSERT_TRUE(f);
  EXPECT_EQ(*f, double(1843.92f));
  EXPECT_EQ(f.value(), double(1843.92f));
  EXPECT_EQ(f, double(1843.92f));
  *f = 2.5;  // assigns through the reference, as *std::optional does
  EXPECT_EQ(f.value_or(0), 2.5);
  const std::optional<double> copy = f;
  EXPECT_EQ(copy, 2.5);
  EXPECT_EQ(OptionalFloat(copy), f);
  EXPECT_NE(OptionalFloat(3.0), f);
  EXPECT_NE(OptionalFloat(), f);
  f.reset();
  EXPECT_FALSE(f.has_value());
  EXPECT_EQ(OptionalFloat(std::optional<double>()), f);
  f = 0.0;  // zero and negative zero are values, not "none"
  EXPECT_TRUE(f.has_value());
  f = -0.0;
  EXPECT_TRUE(f.has_value());
}

// A NaN assigned stays a value (so that the path validator rejects it); it never
// turns into "no value", whatever its bits.
TEST(OptionalFloatTest, NaNIsAValueNotNone) {
  OptionalFloat f = kNaN;
  EXPECT_TRUE(f.has_value());
  EXPECT_TRUE(std::isnan(*f));
  EXPECT_NE(f, OptionalFloat());
  for (uint64_t payload : {1ull, 0x40e3f1ull << 29, 0x000fffffffffffffull, 0x0008e3f100000000ull}) {
    uint64_t bits = 0x7ff0000000000000ull | payload;
    double nan;
    std::memcpy(&nan, &bits, sizeof nan);
    ASSERT_TRUE(std::isnan(nan));
    EXPECT_TRUE(OptionalFloat(nan).has_value()) << std::hex << payload;
    EXPECT_TRUE(OptionalFloat(-nan).has_value()) << std::hex << payload;
  }
  EXPECT_TRUE(OptionalFloat(std::numeric_limits<double>::infinity()).has_value());
}

TEST(OptionalFloatTest, LargeDoublesBecomeInfinite) {
  EXPECT_TRUE(std::isinf(*OptionalFloat(1e300)));  // the path validator rejects it
  EXPECT_EQ(*OptionalFloat(1e-300), 0.0);
}

TEST(OptionalIntTest, ReadsLikeStdOptional) {
  OptionalInt s;
  EXPECT_FALSE(s);
  EXPECT_EQ(s.value_or(-1), -1);
  EXPECT_THROW(s.value(), std::bad_optional_access);
  s = 3;
  EXPECT_EQ(*s, 3);
  EXPECT_EQ(s, 3);
  EXPECT_NE(s, 4);
  ++*s;
  EXPECT_EQ(s.value(), 4);
  const std::optional<int> copy = s;
  EXPECT_EQ(copy, 4);
  EXPECT_EQ(OptionalInt(copy), s);
  EXPECT_TRUE(OptionalInt() < s);
  EXPECT_TRUE(OptionalInt(-5) < s);
  EXPECT_FALSE(s < OptionalInt());
  s = std::nullopt;
  EXPECT_EQ(s, std::nullopt);
  EXPECT_EQ(s, OptionalInt());
}

TEST(OptionalIntTest, EveryIntButTheSentinel) {
  const int lowest = std::numeric_limits<int>::min();
  EXPECT_EQ(*OptionalInt(lowest + 1), lowest + 1);
  EXPECT_EQ(*OptionalInt(std::numeric_limits<int>::max()), std::numeric_limits<int>::max());
  EXPECT_EQ(*OptionalInt(0), 0);
  EXPECT_THROW(OptionalInt{lowest}, std::out_of_range);
  EXPECT_THROW(OptionalInt{std::optional<int>(lowest)}, std::out_of_range);
}

double ErrorDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return AngleBetweenDeg(a, b);
}

// Stored and read back: three coefficients bit for bit, the fourth within a
// few 1e-16 (4.4e-16 seen), qw >= 0; and stored again, the same bits.
void ExpectStoredExactly(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond c = q;  // unit already: only the sign changes
  if (c.w() < 0) c.coeffs() = -c.coeffs();
  const Eigen::Quaterniond back = CompactQuaternion(q).quaternion();
  EXPECT_EQ(CompactQuaternion(back).quaternion().coeffs(), back.coeffs()) << q.coeffs().transpose();
  EXPECT_GE(back.w(), 0);
  EXPECT_LE((back.coeffs() - c.coeffs()).cwiseAbs().maxCoeff(), 1e-15) << q.coeffs().transpose();
  int exact = 0;
  for (int i = 0; i < 4; ++i) exact += back.coeffs()[i] == c.coeffs()[i];
  EXPECT_GE(exact, 3) << q.coeffs().transpose();
}

TEST(CompactQuaternionTest, IdentityAndAxes) {
  EXPECT_EQ(CompactQuaternion().quaternion().coeffs(), Eigen::Quaterniond::Identity().coeffs());
  for (const Eigen::Quaterniond& q :
       {Eigen::Quaterniond(1, 0, 0, 0), Eigen::Quaterniond(0, 1, 0, 0), Eigen::Quaterniond(0, 0, -1, 0),
        Eigen::Quaterniond(0, 0, 0, 1), Eigen::Quaterniond(-1, 0, 0, 0), Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5)}) {
    const Eigen::Quaterniond c = CanonicalQuaternion(q);
    EXPECT_EQ(CompactQuaternion(q).quaternion().coeffs(), c.coeffs()) << q.coeffs().transpose();
  }
}

// Worst case over random rotations and rotations within 1e-12..1e-2 degree of
// a half turn (qw ~ 0, where deriving qw from the others would lose 1e-6
// degree): the rotation read back is off by under 1e-12 degree.
TEST(CompactQuaternionTest, WorstErrorIsBelow1e12DegreeEvenNearAHalfTurn) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double worst_deg = 0;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    q.normalize();
    if (i % 2) {  // a half turn about a random axis, minus a tiny angle
      const double off_deg = std::pow(10.0, -12 + 10 * std::uniform_real_distribution<double>()(rng));
      const Eigen::Vector3d axis = q.vec().normalized();
      q = Eigen::AngleAxisd(DegToRad(180 - off_deg), axis);
      if (i % 4 == 1) q.coeffs() = -q.coeffs();
    }
    ExpectStoredExactly(q);
    worst_deg = std::max(worst_deg, ErrorDeg(q, CompactQuaternion(q).quaternion()));
  }
  EXPECT_LT(worst_deg, 1e-12);
  std::cout << "worst rotation error over 20000 rotations: " << worst_deg << " degree\n";
}

// Two coefficients of equal magnitude (a 90-degree turn): whichever is
// recomputed, storing the result again gives the same quaternion.
TEST(CompactQuaternionTest, TiesStoreTheSameWayTwice) {
  for (double pan : {90.0, -90.0, 270.0}) {
    const Eigen::Quaterniond q = QuaternionFromPanTiltRoll({pan, 0, 0});
    ExpectStoredExactly(q);
    const Eigen::Quaterniond once = CompactQuaternion(q).quaternion();
    const Eigen::Quaterniond twice = CompactQuaternion(once).quaternion();
    EXPECT_EQ(twice.coeffs(), once.coeffs()) << pan;
  }
}

TEST(CompactQuaternionTest, ExactHalfTurnKeepsQwZero) {
  const Eigen::Quaterniond q(0, 0.6, 0, -0.8);
  const Eigen::Quaterniond back = CompactQuaternion(q).quaternion();
  EXPECT_EQ(back.w(), 0);
  EXPECT_EQ(back.x(), 0.6);
  EXPECT_EQ(back.z(), -0.8);
  EXPECT_EQ(ErrorDeg(q, back), 0);
}

TEST(CompactQuaternionTest, NormalisesNearUnitQuaternions) {
  const Eigen::Quaterniond q(0.99999, 0, 0.00436, 0);  // |q| = 1 - 5e-7, a file's rounding
  const CompactQuaternion c(q);
  EXPECT_NEAR(c.norm(), 1, 1e-15);
  EXPECT_LE((c.coeffs() - q.normalized().coeffs()).cwiseAbs().maxCoeff(), 2e-16);
}

// Wrong norms and non-finite values stay recognisable: the validator's
// messages ("not unit length (|q| = 2)", "non-finite") are the original's.
TEST(CompactQuaternionTest, InvalidQuaternionsStayInvalid) {
  EXPECT_EQ(CompactQuaternion(Eigen::Quaterniond(2, 0, 0, 0)).norm(), 2);
  EXPECT_EQ(CompactQuaternion(Eigen::Quaterniond(0, 0, 0, 0)).norm(), 0);
  EXPECT_EQ(CompactQuaternion(Eigen::Quaterniond(1.0011, 0, 0, 0)).norm(), 1.0011);
  EXPECT_FALSE(CompactQuaternion(Eigen::Quaterniond(kNaN, 0, 0, 0)).coeffs().allFinite());
  EXPECT_FALSE(CompactQuaternion(Eigen::Quaterniond(1, std::numeric_limits<double>::infinity(), 0, 0))
                   .coeffs()
                   .allFinite());
  EXPECT_FALSE(CompactQuaternion(Eigen::Quaterniond(1, kNaN, 0, 0)).coeffs().allFinite());
}

TEST(CompactQuaternionTest, ProductsAndConversions) {
  const Eigen::Quaterniond a = QuaternionFromPanTiltRoll({30, -10, 5});
  const Eigen::Quaterniond b = QuaternionFromPanTiltRoll({-70, 20, 1});
  CompactQuaternion ca(a), cb(Eigen::Quaterniond::Identity());
  cb = b;
  const Eigen::Vector3d v(1, 2, 3);
  EXPECT_LT(((ca * v) - a * v).norm(), 1e-15);
  EXPECT_LT(ErrorDeg(ca * cb, a * b), 1e-12);
  EXPECT_LT(ErrorDeg(ca * b, a * b), 1e-12);
  EXPECT_LT(ErrorDeg(a * cb, a * b), 1e-12);
  const Eigen::Quaterniond converted = ca;
  EXPECT_LT(ErrorDeg(converted, a), 1e-12);
  EXPECT_LT((ca.toRotationMatrix() - a.toRotationMatrix()).norm(), 1e-15);
}

TEST(CompactQuaternionTest, SizeIsThreeDoubles) { EXPECT_EQ(sizeof(CompactQuaternion), 24u); }

}  // namespace
}  // namespace hapcine
