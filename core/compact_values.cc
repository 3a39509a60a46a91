#include "core/compact_values.h"

#include <cmath>
#include <cstring>
#include <stdexcept>


namespace hapcine {

std::ostream& operator<<(std::ostream& out, StoredFloat v) { return out << double(v); }

uint32_t OptionalFloat::Bits(StoredFloat v) {
  const float raw = v.raw();
  uint32_t bits;
  std::memcpy(&bits, &raw, sizeof bits);
  return bits;
}

StoredFloat OptionalFloat::Empty() {
  float raw;
  std::memcpy(&raw, &kEmpty, sizeof raw);
  return StoredFloat::FromRaw(raw);
}

void OptionalFloat::Set(double v) {
  // Every NaN becomes the plain quiet NaN, never the "no value" pattern.
  value_ = std::isnan(v) ? StoredFloat(std::numeric_limits<double>::quiet_NaN()) : StoredFloat(v);
}

double OptionalFloat::value() const {
  if (!has_value()) throw std::bad_optional_access();
  return value_;
}

int OptionalInt::Checked(int v) {
  if (v == kEmpty) throw std::out_of_range("OptionalInt cannot hold INT32_MIN");
  return v;
}

int OptionalInt::value() const {
  if (!has_value()) throw std::bad_optional_access();
  return v_;
}

namespace {

constexpr uint64_t kBit62 = uint64_t{1} << 62;
// The first stored word of an invalid quaternion (the norm is in the second):
// 1.5, a magnitude no coefficient of a unit quaternion has.
constexpr uint64_t kInvalid = 0x3ff8000000000000ull;

uint64_t ToBits(double v) {
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

double FromBits(uint64_t b) {
  double v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

// The first coefficient within 1e-9 of the largest magnitude: a rule that a
// coefficient recomputed to the last bit does not change (a 90-degree turn has
// two equal coefficients), so a quaternion read back stores the same way.
int LargestCoefficient(const double coef[4]) {
  double top = 0;
  for (int i = 0; i < 4; ++i) top = std::max(top, std::abs(coef[i]));
  int i = 0;
  while (std::abs(coef[i]) < top * (1 - 1e-9)) ++i;
  return i;
}

}  // namespace

// Coefficients in the order w, x, y, z. The dropped (largest) one's index
// takes bit 62 of words 0 and 1, its sign bit 62 of word 2.
void CompactQuaternion::Set(const Eigen::Quaterniond& q) {
  const double n = q.norm();
  if (!std::isfinite(n) || std::abs(n - 1.0) > kUnitTolerance) {
    word_[0] = kInvalid;
    word_[1] = ToBits(n);
    word_[2] = 0;
    return;
  }
  // Unit to rounding (as read back from here, or from a file this wrote): kept
  // as it is, so that writing, reading and writing again gives the same text.
  const bool unit = std::abs(q.squaredNorm() - 1.0) <= 1e-15;
  Eigen::Quaterniond c = unit ? q : q.normalized();
  if (c.w() < 0) c.coeffs() = -c.coeffs();
  const double coef[4] = {c.w(), c.x(), c.y(), c.z()};
  const int largest = LargestCoefficient(coef);
  for (int i = 0, k = 0; i < 4; ++i) {
    if (i != largest) word_[k++] = ToBits(coef[i]);
  }
  if (largest & 1) word_[0] |= kBit62;
  if (largest & 2) word_[1] |= kBit62;
  if (std::signbit(coef[largest])) word_[2] |= kBit62;
}

Eigen::Quaterniond CompactQuaternion::quaternion() const {
  if (word_[0] == kInvalid) return Eigen::Quaterniond(FromBits(word_[1]), 0, 0, 0);
  const int largest = (word_[0] & kBit62 ? 1 : 0) | (word_[1] & kBit62 ? 2 : 0);
  const bool negative = word_[2] & kBit62;
  double kept[3];
  for (int k = 0; k < 3; ++k) kept[k] = FromBits(word_[k] & ~kBit62);
  const double rest = kept[0] * kept[0] + kept[1] * kept[1] + kept[2] * kept[2];
  const double dropped = std::sqrt(std::max(0.0, 1.0 - rest));
  double coef[4];
  for (int i = 0, k = 0; i < 4; ++i) coef[i] = i == largest ? (negative ? -dropped : dropped) : kept[k++];
  return Eigen::Quaterniond(coef[0], coef[1], coef[2], coef[3]);
}

}  // namespace hapcine
