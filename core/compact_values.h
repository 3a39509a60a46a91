#pragma once
// Compact field types of a camera frame (core/camera_path.h). A film's path
// is held whole in memory (10 million rows for the longest inputs the readers
// accept), so each frame must stay near the size of its text row. These types
// read like the types they replace, so call sites keep compiling:
//   StoredFloat        a double stored in 32 bits (fov_deg)
//   OptionalFloat      std::optional<double> stored in 32 bits (focal_px, confidence)
//   OptionalInt        std::optional<int> stored in 32 bits (shot)
//   CompactQuaternion  a unit Eigen::Quaterniond stored in 24 bytes (world_from_cam)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <optional>
#include <ostream>

namespace hapcine {

// A double kept at single precision: it converts to and from double, so
// arithmetic on it is done in double. Files print it with FormatFloat
// (core/csv.h), the shortest text that reads back to the same value.
class StoredFloat {
 public:
  StoredFloat() = default;
  // Explicit, so that `cond ? stored : 1.0` is a double, not ambiguous.
  explicit StoredFloat(double v) : v_(static_cast<float>(v)) {}
  StoredFloat& operator=(double v) {
    v_ = static_cast<float>(v);
    return *this;
  }
  operator double() const { return v_; }  // NOLINT: implicit, like a double
  StoredFloat& operator+=(double d) { return *this = *this + d; }
  StoredFloat& operator-=(double d) { return *this = *this - d; }
  StoredFloat& operator*=(double d) { return *this = *this * d; }
  StoredFloat& operator/=(double d) { return *this = *this / d; }
  // The stored float itself, bit for bit (OptionalFloat's "no value" pattern).
  static StoredFloat FromRaw(float raw) {
    StoredFloat s;
    s.v_ = raw;
    return s;
  }
  float raw() const { return v_; }

 private:
  float v_ = 0;
};
std::ostream& operator<<(std::ostream& out, StoredFloat v);

// std::optional<double> at single precision. "No value" is one NaN bit
// pattern that no assignment produces: a NaN assigned is kept as a value (the
// path validator then rejects it), never silently read back as "no value".
class OptionalFloat {
 public:
  OptionalFloat() = default;
  OptionalFloat(std::nullopt_t) {}        // NOLINT: implicit, like std::optional
  OptionalFloat(double v) { Set(v); }     // NOLINT
  OptionalFloat(const std::optional<double>& v) {  // NOLINT
    if (v) Set(*v);
  }

  bool has_value() const { return Bits(value_) != kEmpty; }
  explicit operator bool() const { return has_value(); }
  // Undefined without a value, as std::optional; the reference assigns from double.
  StoredFloat& operator*() { return value_; }
  const StoredFloat& operator*() const { return value_; }
  double value() const;  // throws std::bad_optional_access without a value
  double value_or(double fallback) const { return has_value() ? double(value_) : fallback; }
  void reset() { value_ = Empty(); }
  operator std::optional<double>() const {  // NOLINT
    return has_value() ? std::optional<double>(value_) : std::nullopt;
  }

  // As std::optional: equal when both empty, or both set to equal values.
  friend bool operator==(const OptionalFloat& a, const OptionalFloat& b) {
    return a.has_value() == b.has_value() && (!a.has_value() || double(a.value_) == double(b.value_));
  }
  friend bool operator!=(const OptionalFloat& a, const OptionalFloat& b) { return !(a == b); }
  friend bool operator==(const OptionalFloat& a, double b) { return a.has_value() && double(a.value_) == b; }
  friend bool operator!=(const OptionalFloat& a, double b) { return !(a == b); }
  friend bool operator==(const OptionalFloat& a, std::nullopt_t) { return !a.has_value(); }
  friend bool operator!=(const OptionalFloat& a, std::nullopt_t) { return a.has_value(); }

 private:
  static constexpr uint32_t kEmpty = 0x7fc0e3f1u;  // a quiet NaN with a payload
  static uint32_t Bits(StoredFloat v);
  static StoredFloat Empty();
  void Set(double v);

  StoredFloat value_ = Empty();
};

// std::optional<int> in 4 bytes: INT32_MIN means "no value", so that one
// integer cannot be held (assigning it throws std::out_of_range; the CSV
// readers already refuse it as "not an integer").
class OptionalInt {
 public:
  static constexpr int32_t kEmpty = std::numeric_limits<int32_t>::min();

  OptionalInt() = default;
  OptionalInt(std::nullopt_t) {}       // NOLINT: implicit, like std::optional
  OptionalInt(int v) : v_(Checked(v)) {}  // NOLINT
  OptionalInt(const std::optional<int>& v) : v_(v ? Checked(*v) : kEmpty) {}  // NOLINT

  bool has_value() const { return v_ != kEmpty; }
  explicit operator bool() const { return has_value(); }
  int& operator*() { return v_; }  // undefined without a value, as std::optional
  const int& operator*() const { return v_; }
  int value() const;  // throws std::bad_optional_access without a value
  int value_or(int fallback) const { return has_value() ? v_ : fallback; }
  void reset() { v_ = kEmpty; }
  operator std::optional<int>() const {  // NOLINT
    return has_value() ? std::optional<int>(v_) : std::nullopt;
  }

  friend bool operator==(const OptionalInt& a, const OptionalInt& b) { return a.v_ == b.v_; }
  friend bool operator!=(const OptionalInt& a, const OptionalInt& b) { return a.v_ != b.v_; }
  friend bool operator==(const OptionalInt& a, int b) { return a.has_value() && a.v_ == b; }
  friend bool operator!=(const OptionalInt& a, int b) { return !(a == b); }
  friend bool operator==(const OptionalInt& a, std::nullopt_t) { return !a.has_value(); }
  friend bool operator!=(const OptionalInt& a, std::nullopt_t) { return a.has_value(); }
  // As std::optional: no value orders before every value.
  friend bool operator<(const OptionalInt& a, const OptionalInt& b) {
    return b.has_value() && (!a.has_value() || a.v_ < b.v_);
  }

 private:
  static int Checked(int v);
  int32_t v_ = kEmpty;
};

// A rotation stored as the three smallest coefficients of its unit quaternion
// (24 bytes instead of Eigen's 16-byte aligned 32): the largest coefficient,
// at least 1/2, is recomputed from them, which loses nothing measurable (a few
// 1e-16 on it, at any angle including 180 degrees where qw = 0). Which
// coefficient was dropped, and its sign, sit in bit 62 of the stored doubles,
// which is 0 for any number of magnitude below 2.
// Reads back normalised with qw >= 0 (CanonicalQuaternion). A quaternion whose
// norm is off by more than kUnitTolerance, or not finite, is kept as invalid:
// it reads back as (|q|, 0, 0, 0), which the path validator reports exactly as
// it reported the original (wrong norm, or non-finite).
class CompactQuaternion {
 public:
  static constexpr double kUnitTolerance = 1e-3;  // the camera path's rule

  CompactQuaternion() : CompactQuaternion(Eigen::Quaterniond::Identity()) {}
  // Explicit, so that Eigen's own products never convert to this type.
  explicit CompactQuaternion(const Eigen::Quaterniond& q) { Set(q); }
  CompactQuaternion& operator=(const Eigen::Quaterniond& q) {
    Set(q);
    return *this;
  }
  operator Eigen::Quaterniond() const { return quaternion(); }  // NOLINT
  Eigen::Quaterniond quaternion() const;

  // The Eigen::Quaterniond methods the code uses, on the unpacked quaternion.
  double w() const { return quaternion().w(); }
  double x() const { return quaternion().x(); }
  double y() const { return quaternion().y(); }
  double z() const { return quaternion().z(); }
  Eigen::Vector4d coeffs() const { return quaternion().coeffs(); }
  Eigen::Vector3d vec() const { return quaternion().vec(); }
  double norm() const { return quaternion().norm(); }
  Eigen::Matrix3d toRotationMatrix() const { return quaternion().toRotationMatrix(); }
  Eigen::Quaterniond conjugate() const { return quaternion().conjugate(); }
  Eigen::Quaterniond inverse() const { return quaternion().inverse(); }
  Eigen::Quaterniond normalized() const { return quaternion().normalized(); }
  double angularDistance(const Eigen::Quaterniond& other) const {
    return quaternion().angularDistance(other);
  }
  Eigen::Quaterniond slerp(double t, const Eigen::Quaterniond& other) const {
    return quaternion().slerp(t, other);
  }

 private:
  void Set(const Eigen::Quaterniond& q);
  uint64_t word_[3];
};

inline Eigen::Quaterniond operator*(const CompactQuaternion& a, const CompactQuaternion& b) {
  return a.quaternion() * b.quaternion();
}
inline Eigen::Quaterniond operator*(const CompactQuaternion& a, const Eigen::Quaterniond& b) {
  return a.quaternion() * b;
}
inline Eigen::Quaterniond operator*(const Eigen::Quaterniond& a, const CompactQuaternion& b) {
  return a * b.quaternion();
}
inline Eigen::Vector3d operator*(const CompactQuaternion& a, const Eigen::Vector3d& v) {
  return a.quaternion() * v;
}

}  // namespace hapcine
